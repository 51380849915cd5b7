/* SPDX-License-Identifier: MIT */
/* SM_API marks what the libraries export. A shared build (SUPERMODAL_SHARED) compiles with hidden
 * visibility, so only declarations marked SM_API are callable from outside the library that defines
 * them; a static build exports everything and SM_API is empty. The build defines
 * SUPERMODAL_SHARED_BUILD while compiling a shared library and hands SUPERMODAL_SHARED_LIBS to every
 * target that links one (CMake usage requirement), so hosts need do nothing. Plain C: the C API
 * (supermodal/supermodal.h) uses it too. */
#ifndef SUPERMODAL_API_H
#define SUPERMODAL_API_H

#if defined(SUPERMODAL_SHARED_BUILD) || defined(SUPERMODAL_SHARED_LIBS)
#if defined(_WIN32)
/* Windows would need a macro per library (export while building it, import while using it); the
 * libraries are built for ELF platforms only. */
#error "supermodal's shared libraries are built for ELF platforms only"
#else
#define SM_API __attribute__((visibility("default")))
#endif
#else
#define SM_API
#endif

#endif /* SUPERMODAL_API_H */
