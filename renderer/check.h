#pragma once

#include <cstdio>
#include <cstdlib>

// CLIPBLUR_DCHECK(condition): a hot path's precondition or invariant, checked in the sanitizer build
// (CLIPBLUR_CHECKS, set with CLIPBLUR_SANITIZE) and compiled out elsewhere, so release speed does not pay
// for it. A failure is a renderer bug: it names the condition and aborts.
#ifdef CLIPBLUR_CHECKS
#define CLIPBLUR_DCHECK(condition)                                                                       \
    do {                                                                                                 \
        if (!(condition)) {                                                                              \
            std::fprintf(stderr, "%s:%d: invariant failed: %s\n", __FILE__, __LINE__, #condition);      \
            std::abort();                                                                                \
        }                                                                                                \
    } while (false)
#else
#define CLIPBLUR_DCHECK(condition) \
    do {                           \
    } while (false && (condition))
#endif
