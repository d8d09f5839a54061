// Elementary functions of many floats at once, through glibc's vector maths library (libmvec, part
// of libc6 on Debian 12): what the curl op asks of millions of points a run. libm's scalar sincosf
// costs about 5.8 ns a value on the project's machine, libmvec's four-lane one about 2.1 ns.
//
// Each value is a pure function of its argument (a lane's result does not depend on the others in
// its register, on where a run is cut into registers, or on n), so results do not depend on
// batching or the thread count. They are libmvec's (within 4 ulp of the true value, its documented
// bound), not libm's: the same argument may differ from std::sin in the last bits. Where libmvec is
// missing (not x86-64) the scalar functions answer.
#pragma once

#include <cstddef>

namespace groom {

/// s[i] = sin(a[i]) and c[i] = cos(a[i]) for i < n (radians).
void sin_cos(const float* a, size_t n, float* s, float* c);

/// c[i] = cos(a[i]) for i < n (radians).
void cos_of(const float* a, size_t n, float* c);

/// y[i] = pow(x[i], e) for i < n; x[i] >= 0 (what the Lame curve raises |cos| and |sin| to).
void pow_of(const float* x, float e, size_t n, float* y);

}  // namespace groom
