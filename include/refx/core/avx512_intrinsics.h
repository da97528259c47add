// <immintrin.h> for the translation units compiled with AVX-512 flags (*_avx512.cpp):
// GCC 12's AVX-512 intrinsics warn about their own undefined pass-through operands.
#pragma once
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <immintrin.h>
#pragma GCC diagnostic pop
