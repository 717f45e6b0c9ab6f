#pragma once
// The memo cache: a node's outputs kept under the hash of everything they depend on (type,
// version, parameters, effects read, the inputs' hashes), shared by the runs of a sweep and by its
// threads. It is bounded: past `capacity` entries the least recently used one is dropped, so a
// sweep over thousands of designs keeps what its cases share (one part for many speeds)
// without growing without end.
#include <mechgraph/node.hpp>

#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <unordered_map>

namespace mechgraph {

class MemoCache {
 public:
  static constexpr std::size_t default_capacity = 4096;
  explicit MemoCache(std::size_t capacity = default_capacity);

  /// The entry under `key` (and marks it used), or null.
  std::shared_ptr<const OutputSet> find(std::uint64_t key);
  /// Stores (or replaces) an entry; drops the least recently used ones beyond the capacity.
  void store(std::uint64_t key, std::shared_ptr<const OutputSet> outputs);
  void erase(std::uint64_t key);

  std::size_t size() const;
  std::size_t capacity() const { return capacity_; }
  /// Lookups that found an entry, lookups that did not, entries dropped for room.
  std::uint64_t hits() const;
  std::uint64_t misses() const;
  std::uint64_t evictions() const;

 private:
  using Entry = std::pair<std::uint64_t, std::shared_ptr<const OutputSet>>;
  mutable std::mutex mutex_;
  std::size_t capacity_;
  std::list<Entry> recency_;  // most recently used first
  std::unordered_map<std::uint64_t, std::list<Entry>::iterator> entries_;
  std::uint64_t hits_ = 0, misses_ = 0, evictions_ = 0;
};

}  // namespace mechgraph
