// Embree's errors become ours (trace/embree_device.h): an error Embree reports to the device's
// callback is thrown by the next check as an EmbreeError, one line in Embree's words with what we
// were doing, and a device Embree refuses is one too. The errors are provoked with invalid values
// that Embree checks and refuses without side effects (an invalid build quality, a configuration
// that is no number).
#include <gtest/gtest.h>

#include <string>

#include "trace/embree_device.h"
#include "trace/embree_scene.h"

namespace softtrace {
namespace {

std::string thrown(EmbreeDevice& device, const char* what) {
  try {
    device.check(what);
  } catch (const EmbreeError& e) {
    return e.what();
  }
  return "";
}

TEST(EmbreeErrors, AnErrorOfTheCallbackIsThrownByTheNextCheck) {
  EmbreeDevice device;
  RTCScene scene = rtcNewScene(device.get());
  ASSERT_NE(scene, nullptr);
  EXPECT_FALSE(device.failed());
  EXPECT_EQ(thrown(device, "creating the scene"), "");  // nothing to report
  rtcSetSceneBuildQuality(scene, static_cast<RTCBuildQuality>(99));
  EXPECT_TRUE(device.failed());
  EXPECT_EQ(thrown(device, "setting the build quality"),
            "Embree failed setting the build quality: error: invalid build quality");
  // Thrown once: the device is usable again.
  EXPECT_FALSE(device.failed());
  EXPECT_EQ(thrown(device, "again"), "");
  rtcReleaseScene(scene);
}

TEST(EmbreeErrors, TheFirstErrorIsTheOneReported) {
  EmbreeDevice device;
  RTCScene scene = rtcNewScene(device.get());
  rtcSetSceneBuildQuality(scene, static_cast<RTCBuildQuality>(99));
  RTCGeometry geometry = rtcNewGeometry(device.get(), static_cast<RTCGeometryType>(77));
  EXPECT_EQ(geometry, nullptr);
  EXPECT_EQ(thrown(device, "building"), "Embree failed building: error: invalid build quality");
  rtcReleaseScene(scene);
}

TEST(EmbreeErrors, ADeviceEmbreeRefusesIsAnError) {
  try {
    EmbreeDevice device("threads=many");
    FAIL() << "Embree took threads=many";
  } catch (const EmbreeError& e) {
    EXPECT_EQ(std::string(e.what()), "Embree failed creating its device: error");
  }
}

}  // namespace
}  // namespace softtrace
