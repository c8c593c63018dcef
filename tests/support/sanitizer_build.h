// Whether the code under test runs under a sanitizer. The library and the program are built with
// it; the test programs' own files may not be (an ASan build compiles them without
// instrumentation, tests/CMakeLists.txt says why), so CMake tells them by PERIFLEX_SANITIZER_BUILD.
#pragma once

#if defined(PERIFLEX_SANITIZER_BUILD) || defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define PERIFLEX_UNDER_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define PERIFLEX_UNDER_SANITIZER 1
#endif
#endif
#ifndef PERIFLEX_UNDER_SANITIZER
#define PERIFLEX_UNDER_SANITIZER 0
#endif
