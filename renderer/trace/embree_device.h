// An Embree device whose errors become ours. Embree reports an error to the device's error
// callback (rtcSetDeviceErrorFunction), on the thread of the failing call: ours, or one of its
// build threads. Our intersect callbacks report theirs the same way (fail_in_callback): they
// catch what they throw rather than let rtcIntersect1 catch it, since softtrace-core's own C++
// runtime and libgcc cannot unwind through libembree3's frames, whose handlers are the shared
// runtime's (the process aborts: tests/renderer/cli/test_core_runtime.cpp). No exception may
// cross Embree's C code, so the callback only keeps the first error; check() after each call we
// make throws it as an EmbreeError (embree_scene.h), which the command line reports as one line;
// the ray that failed is not used.
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
  // Records the exception being handled (called in a catch block of one of our callbacks) as the
  // device's error, as Embree records what a callback throws: std::bad_alloc as out of memory,
  // any other exception as an error in its own words.
  void fail_in_callback() noexcept;

 private:
  static void on_error(void* self, RTCError code, const char* message);

  RTCDevice device_ = nullptr;
  std::atomic<bool> failed_{false};
  std::mutex mutex_;  // the callback may run on several of Embree's threads at once
  RTCError code_ = RTC_ERROR_NONE;
  std::string message_;
};

}  // namespace softtrace
