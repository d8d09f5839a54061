#include "kernel/math/vector_math.h"

#include <cmath>
#include <cstring>

#if defined(__x86_64__) && defined(GROOM_HAVE_LIBMVEC)
#include <emmintrin.h>

// The x86-64 vector function ABI's names for libmvec's SSE variants (4 lanes): callable from any
// x86-64 (glibc picks its SSE4.1 code or a fallback at load time). GCC calls them itself only under
// -ffast-math, which would change the rest of the arithmetic, so they are called by name.
extern "C" __m128 _ZGVbN4v_sinf(__m128);
extern "C" __m128 _ZGVbN4v_cosf(__m128);
extern "C" __m128 _ZGVbN4vv_powf(__m128, __m128);
#define GROOM_VECTOR_MATH 1
#endif

namespace groom {

#ifdef GROOM_VECTOR_MATH

namespace {

/// Four lanes at a time; the last partial group goes through a zero-padded copy (the padding's
/// results are dropped, and no lane's value depends on another's).
template <class Lanes>
void in_fours(size_t n, Lanes lanes)
{
    size_t i = 0;
    for (; i + 4 <= n; i += 4) lanes(i, size_t(4));
    if (i < n) lanes(i, n - i);
}

__m128 load(const float* a, size_t count)
{
    if (count == 4) return _mm_loadu_ps(a);
    float pad[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    std::memcpy(pad, a, count * sizeof(float));
    return _mm_loadu_ps(pad);
}

void store(float* out, __m128 v, size_t count)
{
    if (count == 4) return _mm_storeu_ps(out, v);
    float pad[4];
    _mm_storeu_ps(pad, v);
    std::memcpy(out, pad, count * sizeof(float));
}

}  // namespace

void sin_cos(const float* a, size_t n, float* s, float* c)
{
    in_fours(n, [&](size_t i, size_t count) {
        const __m128 x = load(a + i, count);
        store(s + i, _ZGVbN4v_sinf(x), count);
        store(c + i, _ZGVbN4v_cosf(x), count);
    });
}

void cos_of(const float* a, size_t n, float* c)
{
    in_fours(n, [&](size_t i, size_t count) { store(c + i, _ZGVbN4v_cosf(load(a + i, count)), count); });
}

void pow_of(const float* x, float e, size_t n, float* y)
{
    const __m128 ev = _mm_set1_ps(e);
    in_fours(n, [&](size_t i, size_t count) { store(y + i, _ZGVbN4vv_powf(load(x + i, count), ev), count); });
}

#else

void sin_cos(const float* a, size_t n, float* s, float* c)
{
    for (size_t i = 0; i < n; ++i) s[i] = std::sin(a[i]), c[i] = std::cos(a[i]);
}

void cos_of(const float* a, size_t n, float* c)
{
    for (size_t i = 0; i < n; ++i) c[i] = std::cos(a[i]);
}

void pow_of(const float* x, float e, size_t n, float* y)
{
    for (size_t i = 0; i < n; ++i) y[i] = std::pow(x[i], e);
}

#endif

}  // namespace groom
