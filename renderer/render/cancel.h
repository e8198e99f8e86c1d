// A frame's cancel flag (RenderOptions::cancel: a signal, Python's Ctrl-C), seen where the work
// is: before every sample, every light and every shadow or reflected ray. One sample may cast
// thousands of rays (an area light is up to 64x64 of them, per light), so a check per sample
// alone could leave a signal waiting for seconds. A cancelled frame is thrown away: whatever the
// code returns once the flag is set is never seen.
#pragma once

#include <atomic>

namespace softtrace {

// A relaxed load: nothing is read through the flag, and it costs nothing beside a ray.
inline bool cancel_requested(const std::atomic<bool>* cancel) {
  return cancel && cancel->load(std::memory_order_relaxed);
}

}  // namespace softtrace
