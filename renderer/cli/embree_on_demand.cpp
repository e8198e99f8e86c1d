// The command line's Embree: the rtc* functions the tracer calls (trace/embree_scene.cpp and
// trace/embree_device.cpp), defined here so that softtrace-core does not link libembree3 (the
// linker's --as-needed then leaves it out, as exr_on_demand.cpp leaves OpenEXR out). Loading and
// relocating Embree at the program's start cost every run about 0.5 ms of CPU, and a scene that
// the direct paths trace (one field, alone or beside a few primitives, nothing transparent:
// EmbreeScene) never calls it. The first call opens the library (SOFTTRACE_EMBREE_LIBRARY, its
// soname) and finds all of its functions at once; each call here then forwards to Embree's own.
// Without the library, rtcNewDevice returns null and rtcGetDeviceError RTC_ERROR_UNKNOWN, so that
// the device's creation fails as a failure of Embree's own would (EmbreeDevice); nothing else is
// called without a device.
#include <dlfcn.h>
#include <embree3/rtcore.h>

namespace {

// Embree's functions, all found or none (`loaded` false).
struct Embree {
  decltype(&::rtcNewDevice) rtcNewDevice = nullptr;
  decltype(&::rtcReleaseDevice) rtcReleaseDevice = nullptr;
  decltype(&::rtcGetDeviceError) rtcGetDeviceError = nullptr;
  decltype(&::rtcSetDeviceErrorFunction) rtcSetDeviceErrorFunction = nullptr;
  decltype(&::rtcNewScene) rtcNewScene = nullptr;
  decltype(&::rtcReleaseScene) rtcReleaseScene = nullptr;
  decltype(&::rtcCommitScene) rtcCommitScene = nullptr;
  decltype(&::rtcNewGeometry) rtcNewGeometry = nullptr;
  decltype(&::rtcReleaseGeometry) rtcReleaseGeometry = nullptr;
  decltype(&::rtcCommitGeometry) rtcCommitGeometry = nullptr;
  decltype(&::rtcAttachGeometry) rtcAttachGeometry = nullptr;
  decltype(&::rtcSetGeometryUserPrimitiveCount) rtcSetGeometryUserPrimitiveCount = nullptr;
  decltype(&::rtcSetGeometryUserData) rtcSetGeometryUserData = nullptr;
  decltype(&::rtcSetGeometryBoundsFunction) rtcSetGeometryBoundsFunction = nullptr;
  decltype(&::rtcSetGeometryIntersectFunction) rtcSetGeometryIntersectFunction = nullptr;
  decltype(&::rtcSetGeometryOccludedFunction) rtcSetGeometryOccludedFunction = nullptr;
  decltype(&::rtcSetGeometryIntersectFilterFunction) rtcSetGeometryIntersectFilterFunction =
      nullptr;
  decltype(&::rtcSetNewGeometryBuffer) rtcSetNewGeometryBuffer = nullptr;
  decltype(&::rtcIntersect1) rtcIntersect1 = nullptr;
  decltype(&::rtcOccluded1) rtcOccluded1 = nullptr;
  bool loaded = false;
};

template <class F>
bool find(void* library, const char* name, F*& function) {
  function = reinterpret_cast<F*>(::dlsym(library, name));
  return function != nullptr;
}

Embree load() {
  Embree e;
  void* library = ::dlopen(SOFTTRACE_EMBREE_LIBRARY, RTLD_NOW | RTLD_LOCAL);
  e.loaded =
      library && find(library, "rtcNewDevice", e.rtcNewDevice) &&
      find(library, "rtcReleaseDevice", e.rtcReleaseDevice) &&
      find(library, "rtcGetDeviceError", e.rtcGetDeviceError) &&
      find(library, "rtcSetDeviceErrorFunction", e.rtcSetDeviceErrorFunction) &&
      find(library, "rtcNewScene", e.rtcNewScene) &&
      find(library, "rtcReleaseScene", e.rtcReleaseScene) &&
      find(library, "rtcCommitScene", e.rtcCommitScene) &&
      find(library, "rtcNewGeometry", e.rtcNewGeometry) &&
      find(library, "rtcReleaseGeometry", e.rtcReleaseGeometry) &&
      find(library, "rtcCommitGeometry", e.rtcCommitGeometry) &&
      find(library, "rtcAttachGeometry", e.rtcAttachGeometry) &&
      find(library, "rtcSetGeometryUserPrimitiveCount", e.rtcSetGeometryUserPrimitiveCount) &&
      find(library, "rtcSetGeometryUserData", e.rtcSetGeometryUserData) &&
      find(library, "rtcSetGeometryBoundsFunction", e.rtcSetGeometryBoundsFunction) &&
      find(library, "rtcSetGeometryIntersectFunction", e.rtcSetGeometryIntersectFunction) &&
      find(library, "rtcSetGeometryOccludedFunction", e.rtcSetGeometryOccludedFunction) &&
      find(library, "rtcSetGeometryIntersectFilterFunction",
           e.rtcSetGeometryIntersectFilterFunction) &&
      find(library, "rtcSetNewGeometryBuffer", e.rtcSetNewGeometryBuffer) &&
      find(library, "rtcIntersect1", e.rtcIntersect1) &&
      find(library, "rtcOccluded1", e.rtcOccluded1);
  return e;
}

// Loaded at the first call; a function-local static, so that a ray's call (rtcIntersect1) costs
// one load and branch more than a direct call.
const Embree& embree() {
  static const Embree e = load();
  return e;
}

}  // namespace

RTCDevice rtcNewDevice(const char* config) {
  const Embree& e = embree();
  return e.loaded ? e.rtcNewDevice(config) : nullptr;
}

RTCError rtcGetDeviceError(RTCDevice device) {
  const Embree& e = embree();
  return e.loaded ? e.rtcGetDeviceError(device) : RTC_ERROR_UNKNOWN;
}

void rtcReleaseDevice(RTCDevice device) {
  embree().rtcReleaseDevice(device);
}

void rtcSetDeviceErrorFunction(RTCDevice device, RTCErrorFunction error, void* user) {
  embree().rtcSetDeviceErrorFunction(device, error, user);
}

RTCScene rtcNewScene(RTCDevice device) {
  return embree().rtcNewScene(device);
}

void rtcReleaseScene(RTCScene scene) {
  embree().rtcReleaseScene(scene);
}

void rtcCommitScene(RTCScene scene) {
  embree().rtcCommitScene(scene);
}

RTCGeometry rtcNewGeometry(RTCDevice device, enum RTCGeometryType type) {
  return embree().rtcNewGeometry(device, type);
}

void rtcReleaseGeometry(RTCGeometry geometry) {
  embree().rtcReleaseGeometry(geometry);
}

void rtcCommitGeometry(RTCGeometry geometry) {
  embree().rtcCommitGeometry(geometry);
}

unsigned int rtcAttachGeometry(RTCScene scene, RTCGeometry geometry) {
  return embree().rtcAttachGeometry(scene, geometry);
}

void rtcSetGeometryUserPrimitiveCount(RTCGeometry geometry, unsigned int count) {
  embree().rtcSetGeometryUserPrimitiveCount(geometry, count);
}

void rtcSetGeometryUserData(RTCGeometry geometry, void* data) {
  embree().rtcSetGeometryUserData(geometry, data);
}

void rtcSetGeometryBoundsFunction(RTCGeometry geometry, RTCBoundsFunction bounds, void* user) {
  embree().rtcSetGeometryBoundsFunction(geometry, bounds, user);
}

void rtcSetGeometryIntersectFunction(RTCGeometry geometry, RTCIntersectFunctionN intersect) {
  embree().rtcSetGeometryIntersectFunction(geometry, intersect);
}

void rtcSetGeometryOccludedFunction(RTCGeometry geometry, RTCOccludedFunctionN occluded) {
  embree().rtcSetGeometryOccludedFunction(geometry, occluded);
}

void rtcSetGeometryIntersectFilterFunction(RTCGeometry geometry, RTCFilterFunctionN filter) {
  embree().rtcSetGeometryIntersectFilterFunction(geometry, filter);
}

void* rtcSetNewGeometryBuffer(RTCGeometry geometry, enum RTCBufferType type, unsigned int slot,
                              enum RTCFormat format, size_t stride, size_t count) {
  return embree().rtcSetNewGeometryBuffer(geometry, type, slot, format, stride, count);
}

void rtcIntersect1(RTCScene scene, struct RTCIntersectContext* context, struct RTCRayHit* rayhit) {
  embree().rtcIntersect1(scene, context, rayhit);
}

void rtcOccluded1(RTCScene scene, struct RTCIntersectContext* context, struct RTCRay* ray) {
  embree().rtcOccluded1(scene, context, ray);
}
