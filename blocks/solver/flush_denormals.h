#pragma once
// FlushDenormals: while alive, subnormal results are flushed to zero and
// subnormal operands read as zero (x86 MXCSR FTZ and DAZ bits); the previous
// mode is restored on destruction.
//
// Why: on a long chain (bench/README.md P3, N = 1000) the far end fills
// with subnormal numbers, and arithmetic on them is microcoded: the solve
// became 5 times slower. Values below 2.2e-308 carry no information at any
// tolerance a run can ask for. Elsewhere than x86 this does nothing.

#if defined(__SSE2__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace mechflow::blocks {

class FlushDenormals {
 public:
#if defined(__SSE2__) || defined(__x86_64__)
  FlushDenormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero); }
  ~FlushDenormals() { _mm_setcsr(saved_); }
#else
  FlushDenormals() = default;
#endif
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

 private:
#if defined(__SSE2__) || defined(__x86_64__)
  static constexpr unsigned kFlushToZero = 0x8000;     // MXCSR bit 15
  static constexpr unsigned kDenormalsAreZero = 0x0040;  // MXCSR bit 6
  unsigned saved_;
#endif
};

}  // namespace mechflow::blocks
