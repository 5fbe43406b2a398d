#pragma once
// FASTRON_API marks what the shared libraries export. Fastron builds with hidden symbols by
// default: its Eigen instantiations are compiled for this machine's SIMD (FASTRON_NATIVE) and,
// exported, would interpose the copies inside other libraries (libompl's, built for plain x86-64,
// 16-byte aligned) and crash them. Every public header opens `namespace FASTRON_API fastron`, so
// the library's own classes and functions are exported and nothing else is.

// The standard attribute syntax, which both GCC and Clang accept on a namespace.
#define FASTRON_API [[gnu::visibility("default")]]
