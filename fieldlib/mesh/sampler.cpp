#include "mesh/sampler.h"

namespace softtrace {

void FieldSampler::prepare(const Box& box, SamplerScratch& s) const {
  if (blobs_) return s.blobs.select(*blobs_, program_, box);
  s.ws.fit(program_);
  prune(program_, box, s.ws);
}

void FieldSampler::values(const double* x, const double* y, const double* z, int n, double* f,
                          SamplerScratch& s) const {
  if (blobs_) return s.blobs.values(x, y, z, n, f);
  softtrace::values(Code(s.ws.view), x, y, z, n, f, s.ws);
}

double FieldSampler::gradient(const Vec3& p, Vec3* grad, SamplerScratch& s) const {
  if (blobs_) return s.blobs.gradient(p, grad);
  s.ws.fit(program_);
  return gradient_pruned(program_, p, grad, s.ws);
}

}  // namespace softtrace
