// Whether this processor runs AVX2 code: the kernels compiled for that target alone (the build
// has no -march, so the same bits on every CI machine) are chosen at run time where it does.
#pragma once

namespace softtrace {

bool cpu_has_avx2();

}  // namespace softtrace
