// An Embree device whose errors become ours. Embree reports an error to the device's error
// callback (rtcSetDeviceErrorFunction), on the thread of the failing call: ours, or one of its
// build threads, or inside rtcIntersect1, which catches what our intersect callbacks throw and
// reports it there instead (the ray would then pass as if it met nothing). No exception may
// cross Embree's C code, so the callback only keeps the first error; check() after each call we
// make throws it as an EmbreeError (embree_scene.h), which the command line reports as one line.
// Included only where Embree is (embree_scene.cpp, and tests that provoke an error).
#pragma once

#include <embree3/rtcore.h>

#include <atomic>
#include <mutex>
#include <string>

namespace softtrace {

class EmbreeDevice {
 public:
  // `config`: rtcNewDevice's configuration string (null: Embree's defaults). Throws EmbreeError
  // when Embree cannot create the device.
  explicit EmbreeDevice(const char* config = nullptr);
  // No device at all (`create` false): for a scene whose rays never reach Embree
  // (EmbreeScene's direct paths). get() is then null and failed() false.
  EmbreeDevice(const char* config, bool create);
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;  // Embree holds `this` for the callback
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice get() const { return device_; }
  // Whether Embree has reported an error not yet thrown: a relaxed load, cheap enough per ray.
  bool failed() const { return failed_.load(std::memory_order_relaxed); }
  // Throws the first error Embree reported since the last check as an EmbreeError naming `what`
  // (what we were doing), and forgets it.
  void check(const char* what);

 private:
  static void on_error(void* self, RTCError code, const char* message);

  RTCDevice device_ = nullptr;
  std::atomic<bool> failed_{false};
  std::mutex mutex_;  // the callback may run on several of Embree's threads at once
  RTCError code_ = RTC_ERROR_NONE;
  std::string message_;
};

}  // namespace softtrace
