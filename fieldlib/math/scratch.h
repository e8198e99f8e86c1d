// Per-call scratch arrays for nodes with a variable number of terms or children: on the stack up
// to N elements (every scene so far), on the heap beyond, so eval() does not allocate.
#pragma once

#include <cstddef>
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

}  // namespace softtrace
