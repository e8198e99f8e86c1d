#include "mesh/sampler.h"

namespace softtrace {

void FieldSampler::prepare(const Box& box, SamplerScratch& s) const {
  s.ws.fit(program_);
  prune(program_, box, s.ws);
}

void FieldSampler::values(const double* x, const double* y, const double* z, int n, double* f,
                          SamplerScratch& s) const {
  softtrace::values(Code(s.ws.view), x, y, z, n, f, s.ws);
}

double FieldSampler::gradient(const Vec3& p, Vec3* grad, SamplerScratch& s) const {
  s.ws.fit(program_);
  if (!blobs_) return gradient_pruned(program_, p, grad, s.ws);
  s.ids.resize(size_t(blobs_->size()));
  return blobs_->gradient(program_, p, grad, s.ids.data());
}

}  // namespace softtrace
