// The static softtrace's Embree: the rtc* functions the tracer calls (trace/embree_scene.cpp and
// trace/embree_device.cpp). Embree is a shared library, which a static program cannot open, and a
// scene the direct paths trace never asks for a device (EmbreeScene); one that does is handed to
// softtrace-core, which opens Embree on demand (embree_on_demand.cpp), right after its load, by
// the rule EmbreeScene reads (core_hand_over.h, trace/direct_paths.h). rtcNewDevice hands over
// too, should a scene pass that check. Every other function takes a device, or a scene or
// geometry made from one, so none can be called here: each ends the process, the mark of a broken
// build rather than of a scene.
#include <embree3/rtcore.h>

#include <cstdio>
#include <cstdlib>

#include "cli/core_hand_over.h"

namespace {

[[noreturn]] void without_device(const char* function) {
  std::fprintf(stderr, "softtrace: %s called without an Embree device\n", function);
  std::abort();
}

}  // namespace

RTCDevice rtcNewDevice(const char*) {
  throw softtrace::NeedsCore{};
}

RTCError rtcGetDeviceError(RTCDevice) {
  without_device(__func__);
}

void rtcReleaseDevice(RTCDevice) {
  without_device(__func__);
}

void rtcSetDeviceErrorFunction(RTCDevice, RTCErrorFunction, void*) {
  without_device(__func__);
}

RTCScene rtcNewScene(RTCDevice) {
  without_device(__func__);
}

void rtcReleaseScene(RTCScene) {
  without_device(__func__);
}

void rtcCommitScene(RTCScene) {
  without_device(__func__);
}

RTCGeometry rtcNewGeometry(RTCDevice, enum RTCGeometryType) {
  without_device(__func__);
}

void rtcReleaseGeometry(RTCGeometry) {
  without_device(__func__);
}

void rtcCommitGeometry(RTCGeometry) {
  without_device(__func__);
}

unsigned int rtcAttachGeometry(RTCScene, RTCGeometry) {
  without_device(__func__);
}

void rtcSetGeometryUserPrimitiveCount(RTCGeometry, unsigned int) {
  without_device(__func__);
}

void rtcSetGeometryUserData(RTCGeometry, void*) {
  without_device(__func__);
}

void rtcSetGeometryBoundsFunction(RTCGeometry, RTCBoundsFunction, void*) {
  without_device(__func__);
}

void rtcSetGeometryIntersectFunction(RTCGeometry, RTCIntersectFunctionN) {
  without_device(__func__);
}

void rtcSetGeometryOccludedFunction(RTCGeometry, RTCOccludedFunctionN) {
  without_device(__func__);
}

void rtcSetGeometryIntersectFilterFunction(RTCGeometry, RTCFilterFunctionN) {
  without_device(__func__);
}

void* rtcSetNewGeometryBuffer(RTCGeometry, enum RTCBufferType, unsigned int, enum RTCFormat, size_t,
                              size_t) {
  without_device(__func__);
}

void rtcIntersect1(RTCScene, struct RTCIntersectContext*, struct RTCRayHit*) {
  without_device(__func__);
}

void rtcOccluded1(RTCScene, struct RTCIntersectContext*, struct RTCRay*) {
  without_device(__func__);
}
