#include "trace/embree_device.h"

#include <exception>
#include <new>
#include <utility>

#include "trace/embree_scene.h"

namespace softtrace {

namespace {

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_UNKNOWN:
      return "error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
  }
  return "error";
}

// "Embree failed <what>: <kind>[: <Embree's words>]", on one line.
std::string error_text(const char* what, RTCError code, const std::string& message) {
  std::string text = std::string("Embree failed ") + what + ": " + error_name(code);
  if (!message.empty()) text += ": " + message;
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

}  // namespace

EmbreeDevice::EmbreeDevice(const char* config) : EmbreeDevice(config, true) {}

EmbreeDevice::EmbreeDevice(const char* config, bool create)
    : device_(create ? rtcNewDevice(config) : nullptr) {
  if (!create) return;
  // A device that failed has no callback yet: Embree keeps its error for a null device.
  if (!device_)
    throw EmbreeError(error_text("creating its device", rtcGetDeviceError(nullptr), ""));
  rtcSetDeviceErrorFunction(device_, on_error, this);
}

EmbreeDevice::~EmbreeDevice() {
  if (device_) rtcReleaseDevice(device_);
}

void EmbreeDevice::on_error(void* self, RTCError code, const char* message) {
  auto* d = static_cast<EmbreeDevice*>(self);
  const std::lock_guard<std::mutex> lock(d->mutex_);
  if (d->code_ != RTC_ERROR_NONE) return;  // the first error is the cause; the rest follow it
  d->code_ = code;
  try {
    d->message_ = message ? message : "";
  } catch (const std::bad_alloc&) {  // no memory for Embree's words: the kind alone
    d->message_.clear();
  }
  d->failed_.store(true, std::memory_order_relaxed);
}

void EmbreeDevice::fail_in_callback() noexcept {
  try {
    throw;
  } catch (const std::bad_alloc&) {
    on_error(this, RTC_ERROR_OUT_OF_MEMORY, nullptr);
  } catch (const std::exception& e) {
    on_error(this, RTC_ERROR_UNKNOWN, e.what());
  } catch (...) {
    on_error(this, RTC_ERROR_UNKNOWN, "an exception of unknown type");
  }
}

void EmbreeDevice::check(const char* what) {
  if (!failed()) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  if (code_ == RTC_ERROR_NONE) return;  // another thread's check took it
  // Forgotten before the text is made: without memory for it, the check throws std::bad_alloc
  // and the device is clear all the same.
  const RTCError code = code_;
  const std::string message = std::move(message_);
  code_ = RTC_ERROR_NONE;
  message_.clear();
  failed_.store(false, std::memory_order_relaxed);
  throw EmbreeError(error_text(what, code, message));
}

}  // namespace softtrace
