// Per-call scratch arrays for nodes with a variable number of terms or children: on the stack up
// to N elements (every scene so far), on the heap beyond, so eval() does not allocate. Scratch
// default-constructs its N stack elements (an Interval zeroes itself); Slots constructs none, for
// hot paths that write each slot before reading it.
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

namespace softtrace {

template <class T, size_t N = 16>
class Scratch {
 public:
  explicit Scratch(size_t n) : heap_(n > N ? n : 0), p_(n > N ? heap_.data() : stack_) {}
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;

  T& operator[](size_t i) { return p_[i]; }
  const T& operator[](size_t i) const { return p_[i]; }
  T* data() { return p_; }

 private:
  T stack_[N];
  std::vector<T> heap_;
  T* p_;
};

// k values of a trivially copyable T for one call, on the stack up to 16 as in Scratch
// but not initialised, and without Scratch's std::vector member: each slot is
// written before it is read (set() or through data()). Scratch<Interval> zeroes all 16 first, and
// both set up and tear down the vector, which an oracle blend pays for every box it is asked.
template <class T>
class Slots {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);

 public:
  static constexpr size_t kStack = 16;

  explicit Slots(size_t k) : heap_(k > kStack ? new T[k] : nullptr) {
    p_ = heap_ ? heap_.get() : reinterpret_cast<T*>(stack_);
  }
  Slots(const Slots&) = delete;
  Slots& operator=(const Slots&) = delete;

  void set(size_t i, const T& v) { new (p_ + i) T(v); }
  T& operator[](size_t i) { return p_[i]; }  // after set(i, ...)
  T* data() { return p_; }

 private:
  alignas(T) unsigned char stack_[kStack * sizeof(T)];
  std::unique_ptr<T[]> heap_;
  T* p_;
};

}  // namespace softtrace
