#pragma once
// The key of this library's C++ layer (c/object_cxx.h, mechgraph.object.cxx/1; c/node_cxx.h,
// mechgraph.node.cxx/1): two libraries whose keys are equal byte for byte lay out every class of
// the SDK's headers, and every standard-library type those classes hold, the same way, so one may
// use the other's C++ domain objects and node types directly. What goes in (pybind11 keys its shared internals the same way):
//  - the SDK's version and a digest of its headers (mechgraph/version.hpp, written by CMake from
//    the headers' contents: the conformance kits and the bridges themselves are left out);
//  - the compiler and its major version (two compilers are assumed to differ, whatever their
//    promises; a plugin built by clang for a gcc-built host then keeps to the C tables);
//  - the standard library, its release and its ABI switches (the dual string ABI, debug mode's
//    other containers), the C++ ABI version, whether RTTI is on, and the language standard.
// A library built with MECHGRAPH_SDK_CXX_SHORTCUT defined to 0 has no key: it neither offers nor
// uses the shortcut (the tests that must see the C tables at work build so). Neither has one built
// with libc++: each library has its own RTTI for the SDK's classes (hidden), and libc++ compares
// type_info by address on ELF, so a dynamic_cast or a catch of NodeError across two libraries
// would fail where libstdc++, which compares the names, succeeds. Nor one built by clang (with
// libstdc++): libstdc++ compares two classes' type information by name unless the compiler marked
// the name as its library's own ('*' first), which gcc does for a class in an anonymous namespace
// and clang 14 does not. Two plugins built by clang from one template, each with its `ThreeArc` in
// an anonymous namespace, would then take each other's objects for their own in a dynamic_cast
// (tests/core/sdk1_objects_test.cpp, "A -> B -> A", found it). Defining the macro to 1 overrides
// either default, at that risk.
#include <mechgraph/version.hpp>

#include <cstring>
#include <version>

#ifndef MECHGRAPH_SDK_CXX_SHORTCUT
#if defined(_LIBCPP_VERSION) || defined(__clang__)
#define MECHGRAPH_SDK_CXX_SHORTCUT 0
#else
#define MECHGRAPH_SDK_CXX_SHORTCUT 1
#endif
#endif

#define MECHGRAPH_DETAIL_TEXT2(x) #x
#define MECHGRAPH_DETAIL_TEXT(x) MECHGRAPH_DETAIL_TEXT2(x)

#if defined(__clang__)
#define MECHGRAPH_DETAIL_KEY_COMPILER "clang-" MECHGRAPH_DETAIL_TEXT(__clang_major__)
#elif defined(__GNUC__)
#define MECHGRAPH_DETAIL_KEY_COMPILER "gcc-" MECHGRAPH_DETAIL_TEXT(__GNUC__)
#else
#define MECHGRAPH_DETAIL_KEY_COMPILER "unknown"
#endif

#if defined(_LIBCPP_VERSION)
#define MECHGRAPH_DETAIL_KEY_STDLIB "libc++-" MECHGRAPH_DETAIL_TEXT(_LIBCPP_VERSION) "-abi" MECHGRAPH_DETAIL_TEXT(_LIBCPP_ABI_VERSION)
#elif defined(__GLIBCXX__)
#if defined(_GLIBCXX_DEBUG)
#define MECHGRAPH_DETAIL_KEY_DEBUG "-debug"
#else
#define MECHGRAPH_DETAIL_KEY_DEBUG ""
#endif
#define MECHGRAPH_DETAIL_KEY_STDLIB \
  "libstdc++-" MECHGRAPH_DETAIL_TEXT(__GLIBCXX__) "-cxx11abi" MECHGRAPH_DETAIL_TEXT(_GLIBCXX_USE_CXX11_ABI) MECHGRAPH_DETAIL_KEY_DEBUG
#else
#define MECHGRAPH_DETAIL_KEY_STDLIB "unknown"
#endif

#if defined(__GXX_ABI_VERSION)
#define MECHGRAPH_DETAIL_KEY_CXXABI "cxxabi" MECHGRAPH_DETAIL_TEXT(__GXX_ABI_VERSION)
#else
#define MECHGRAPH_DETAIL_KEY_CXXABI "cxxabi-unknown"
#endif

// Without RTTI a library's classes carry no type information: the other library's dynamic_cast
// (a BlockEvaluation, a ForecastReads, its own law class) would find none.
#if defined(__GXX_RTTI)
#define MECHGRAPH_DETAIL_KEY_RTTI "rtti"
#else
#define MECHGRAPH_DETAIL_KEY_RTTI "no-rtti"
#endif

namespace mechgraph::detail {

/// This library's key, or nullptr when it keeps to the C tables.
#if MECHGRAPH_SDK_CXX_SHORTCUT
__attribute__((visibility("hidden"))) inline constexpr const char* cxx_abi_key =
    "mechgraph-sdk-" MECHGRAPH_SDK_VERSION "/headers-" MECHGRAPH_SDK_HEADERS_DIGEST "/" MECHGRAPH_DETAIL_KEY_COMPILER
    "/" MECHGRAPH_DETAIL_KEY_STDLIB "/" MECHGRAPH_DETAIL_KEY_CXXABI "/" MECHGRAPH_DETAIL_KEY_RTTI "/std" MECHGRAPH_DETAIL_TEXT(__cplusplus);
#else
__attribute__((visibility("hidden"))) inline constexpr const char* cxx_abi_key = nullptr;
#endif

/// Whether `key`, another library's, is this library's key byte for byte (never for a library
/// without one).
inline bool is_own_cxx_abi_key(const char* key) {
#if MECHGRAPH_SDK_CXX_SHORTCUT
  return key && (key == cxx_abi_key || std::strcmp(key, cxx_abi_key) == 0);
#else
  (void)key;
  return false;
#endif
}

}  // namespace mechgraph::detail
