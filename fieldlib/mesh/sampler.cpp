#include "mesh/sampler.h"

namespace softtrace {

void FieldSampler::prepare(const Box& box, SamplerScratch& s) const {
  if (blobs_) return s.blobs.select(*blobs_, program_, box);
  s.ws.fit(program_);
  prune(program_, box, s.ws);
}

void FieldSampler::prepare_gradients(const Box& box, SamplerScratch& s) const {
  if (blobs_) s.blobs.select(*blobs_, program_, box);
}

void FieldSampler::values(const double* x, const double* y, const double* z, int n, double* f,
                          SamplerScratch& s) const {
  if (blobs_) return s.blobs.values(x, y, z, n, f);
  softtrace::values(Code(s.ws.view), x, y, z, n, f, s.ws);
}

void FieldSampler::grid(const double* xs, const double* ys, const double* zs, const int m[3],
                        double* f, SamplerScratch& s) const {
  if (blobs_) return s.blobs.grid(xs, ys, zs, m, f);
  // The points in grid order, kBatch at a time.
  double x[kBatch], y[kBatch], z[kBatch];
  int n = 0, done = 0;
  for (int k = 0; k < m[2]; ++k)
    for (int j = 0; j < m[1]; ++j)
      for (int i = 0; i < m[0]; ++i) {
        x[n] = xs[i], y[n] = ys[j], z[n] = zs[k];
        if (++n < kBatch) continue;
        values(x, y, z, n, f + done, s);
        done += n;
        n = 0;
      }
  if (n > 0) values(x, y, z, n, f + done, s);
}

double FieldSampler::gradient(const Vec3& p, Vec3* grad, SamplerScratch& s) const {
  if (blobs_) return s.blobs.gradient(p, grad);
  s.ws.fit(program_);
  return gradient_pruned(program_, p, grad, s.ws);
}

}  // namespace softtrace
