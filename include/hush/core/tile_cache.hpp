// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::tile_cache<Key, Tile>: large precomputed data (wavelet noise tiles,
// anisotropic subband tiles) built lazily, once per key, immutable, and
// shared between every noise object that asks for the same key (DESIGN.md:
// "built once per (params, seed), shared between copies, memory reported").
//
//   static hush::tile_cache<my_key, my_tile>& cache() { static hush::tile_cache<...> c; return c; }
//   std::shared_ptr<const my_tile> t = cache().get(key, [&] { return my_tile(key); });
//
// The cache holds weak references: a tile lives as long as some noise object
// holds it, and is rebuilt (bit for bit the same: tiles are deterministic) if
// asked for again after the last holder went away. get() is thread-safe;
// the build runs outside the lock, so two threads asking for the same new
// key at once may both build it, and both receive the one stored first.
// Tile must be constructible by the builder and report its memory as
// `std::size_t bytes() const`. Key needs operator<.
#ifndef HUSH_CORE_TILE_CACHE_HPP
#define HUSH_CORE_TILE_CACHE_HPP

#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

namespace hush {

template <class Key, class Tile>
class tile_cache {
 public:
  tile_cache() = default;
  tile_cache(const tile_cache&) = delete;
  tile_cache& operator=(const tile_cache&) = delete;

  // The tile of `key`, built by build() (returning a Tile) when no live one exists.
  template <class Build>
  std::shared_ptr<const Tile> get(const Key& key, Build&& build) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (auto live = find_live(key)) return live;
    }
    auto made = std::make_shared<const Tile>(std::forward<Build>(build)());
    const std::lock_guard<std::mutex> lock(mutex_);
    if (auto live = find_live(key)) return live;  // another thread stored it meanwhile
    tiles_[key] = made;
    ++builds_;
    return made;
  }

  // Number of tiles alive now, and their memory in bytes (Tile::bytes()).
  std::size_t live_tiles() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::size_t n = 0;
    for (const auto& kv : tiles_) n += kv.second.expired() ? 0 : 1;
    return n;
  }
  std::size_t live_bytes() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::size_t bytes = 0;
    for (const auto& kv : tiles_)
      if (auto t = kv.second.lock()) bytes += t->bytes();
    return bytes;
  }
  // Tiles built so far (a tile rebuilt after expiring counts again).
  std::size_t builds() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return builds_;
  }

 private:
  // The live tile of key, or null; drops an expired entry. Caller holds the lock.
  std::shared_ptr<const Tile> find_live(const Key& key) {
    const auto it = tiles_.find(key);
    if (it == tiles_.end()) return nullptr;
    if (auto t = it->second.lock()) return t;
    tiles_.erase(it);
    return nullptr;
  }

  mutable std::mutex mutex_;
  std::map<Key, std::weak_ptr<const Tile>> tiles_;
  std::size_t builds_ = 0;
};

}  // namespace hush

#endif  // HUSH_CORE_TILE_CACHE_HPP
