#include <mechgraph/memo_cache.hpp>

#include <algorithm>

namespace mechgraph {

MemoCache::MemoCache(std::size_t capacity) : capacity_(std::max<std::size_t>(capacity, 1)) {}

std::shared_ptr<const OutputSet> MemoCache::find(std::uint64_t key) {
  std::lock_guard lock(mutex_);
  auto it = entries_.find(key);
  if (it == entries_.end()) {
    ++misses_;
    return nullptr;
  }
  ++hits_;
  recency_.splice(recency_.begin(), recency_, it->second);
  return it->second->second;
}

void MemoCache::store(std::uint64_t key, std::shared_ptr<const OutputSet> outputs) {
  std::lock_guard lock(mutex_);
  if (auto it = entries_.find(key); it != entries_.end()) {
    it->second->second = std::move(outputs);
    recency_.splice(recency_.begin(), recency_, it->second);
    return;
  }
  recency_.emplace_front(key, std::move(outputs));
  entries_[key] = recency_.begin();
  while (entries_.size() > capacity_) {
    entries_.erase(recency_.back().first);
    recency_.pop_back();
    ++evictions_;
  }
}

void MemoCache::erase(std::uint64_t key) {
  std::lock_guard lock(mutex_);
  if (auto it = entries_.find(key); it != entries_.end()) {
    recency_.erase(it->second);
    entries_.erase(it);
  }
}

std::size_t MemoCache::size() const {
  std::lock_guard lock(mutex_);
  return entries_.size();
}

std::uint64_t MemoCache::hits() const {
  std::lock_guard lock(mutex_);
  return hits_;
}

std::uint64_t MemoCache::misses() const {
  std::lock_guard lock(mutex_);
  return misses_;
}

std::uint64_t MemoCache::evictions() const {
  std::lock_guard lock(mutex_);
  return evictions_;
}

}  // namespace mechgraph
