// Whether this test program is built with AddressSanitizer or ThreadSanitizer, whichever compiler
// built it: gcc defines __SANITIZE_ADDRESS__ and __SANITIZE_THREAD__, clang 14 answers only through
// __has_feature (CI's ASan build uses clang, its ThreadSanitizer build gcc).
#pragma once

#if defined(__SANITIZE_ADDRESS__)
#define MECHGRAPH_TEST_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MECHGRAPH_TEST_ADDRESS_SANITIZER 1
#endif
#endif

#if defined(__SANITIZE_THREAD__)
#define MECHGRAPH_TEST_THREAD_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define MECHGRAPH_TEST_THREAD_SANITIZER 1
#endif
#endif
