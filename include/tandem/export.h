// TANDEM_API marks what a shared libtandem exports: the public classes and functions of
// include/tandem/. The library is compiled with hidden visibility (-fvisibility=hidden
// -fvisibility-inlines-hidden), so everything else stays inside it.
//
// TANDEM_BUILDING_LIBRARY is defined while compiling the library; TANDEM_SHARED when it is shared
// (find_package(Tandem) and tandem.pc define it for its users).
#pragma once

#if defined(_WIN32)
#if defined(TANDEM_SHARED) && defined(TANDEM_BUILDING_LIBRARY)
#define TANDEM_API __declspec(dllexport)
#elif defined(TANDEM_SHARED)
#define TANDEM_API __declspec(dllimport)
#else
#define TANDEM_API
#endif
#elif defined(__GNUC__) || defined(__clang__)
#define TANDEM_API __attribute__((visibility("default")))
#else
#define TANDEM_API
#endif
