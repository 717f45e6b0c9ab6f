#pragma once
// Large arrays of numbers written once from end to end (a study's design, its outputs' values,
// its Sobol' rows): reserved with the kernel asked to back them by transparent huge pages (2 MiB)
// where it has them. The first write to each 4 KiB page is a page fault, and on a virtual machine
// a trap to the hypervisor: a study of 10^6 cases touched about 260 MB for the first time, which
// took a tenth of its run on this project's machine (docs/methods/uncertainty.md, "Where the time
// goes"). Advice only: the contents and every result are the same with or without it.
#include <cstddef>
#include <string>
#include <vector>

namespace mechgraph {

/// Arrays of at least this many bytes are advised (a huge page is 2 MiB on x86-64: smaller arrays
/// gain nothing).
inline constexpr std::size_t large_array_bytes = std::size_t{4} << 20;

/// Asks the kernel to back the whole pages inside [data, data + bytes) by transparent huge pages
/// (madvise MADV_HUGEPAGE, Linux). True when the kernel took the advice; false (and nothing done)
/// where the range holds no whole page or the system has no such pages or declines.
bool advise_huge_pages(void* data, std::size_t bytes);

/// v.reserve(n), its storage advised as above when it is large. Call it before the elements are
/// written: pages already touched stay as they are.
template <class T>
void reserve_large(std::vector<T>& v, std::size_t n) {
  v.reserve(n);
  if (v.capacity() * sizeof(T) >= large_array_bytes) advise_huge_pages(v.data(), v.capacity() * sizeof(T));
}

/// The same for text kept end to end in one string (a table's written cells).
inline void reserve_large(std::string& s, std::size_t n) {
  s.reserve(n);
  if (s.capacity() >= large_array_bytes) advise_huge_pages(s.data(), s.capacity());
}

}  // namespace mechgraph
