// The interiors a ray travels in: POV-Ray 3.7's interior list (backend/render/trace.cpp,
// Trace::ComputeRefraction). A transmitted ray takes its parent's list with the surface it
// passes entered or left; a mirror ray keeps its parent's; a shadow ray starts with the shaded
// ray's and enters or leaves at each transparent surface it crosses. The tracer reads it too: a
// field object in the list is one whose solid the ray is inside, whose surface it then finds
// where it leaves that solid (EmbreeScene::intersect); CSGs, primitives and meshes find their
// exits from inside on their own.
#pragma once

namespace softtrace {

class Interiors {
 public:
  // Nested or overlapping transparent objects deeper than this are not entered (the transmitted
  // light is lost there, docs/math.md §12.6).
  static constexpr int kMax = 16;
  struct Entry {
    int object;  // index into Scene::objects
    double ior;  // its interior's index of refraction
  };

  bool empty() const { return size_ == 0; }
  int size() const { return size_; }
  // The innermost: the object entered last. Not for an empty list.
  const Entry& back() const { return entries_[size_ - 1]; }
  bool contains(int object) const {
    for (int i = 0; i < size_; ++i)
      if (entries_[i].object == object) return true;
    return false;
  }
  // Appends `object`; false (and nothing changes) when the list is full.
  bool push(int object, double ior) {
    if (size_ == kMax) return false;
    entries_[size_++] = {object, ior};
    return true;
  }
  // Removes `object` where it is in the list, keeping the others' order; false if it is not.
  bool remove(int object) {
    for (int i = 0; i < size_; ++i)
      if (entries_[i].object == object) {
        for (int j = i + 1; j < size_; ++j) entries_[j - 1] = entries_[j];
        --size_;
        return true;
      }
    return false;
  }

 private:
  Entry entries_[kMax];
  int size_ = 0;
};

}  // namespace softtrace
