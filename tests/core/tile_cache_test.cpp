// Tests for hush/core/tile_cache.hpp: one live tile per key, shared between
// every holder, rebuilt after the last holder lets go, memory reported, and
// safe to use from several threads.
#include <doctest/doctest.h>

#include <atomic>
#include <cstddef>
#include <memory>
#include <thread>
#include <vector>

#include "hush/core/tile_cache.hpp"

namespace {

struct fake_tile {
  explicit fake_tile(int n) : values(static_cast<std::size_t>(n), n) {}
  std::vector<int> values;
  std::size_t bytes() const { return values.size() * sizeof(int); }
};

}  // namespace

TEST_CASE("tile_cache: a key is built once while it is held, and shared") {
  hush::tile_cache<int, fake_tile> cache;
  int builds = 0;
  auto make = [&](int n) {
    return [&builds, n] {
      ++builds;
      return fake_tile(n);
    };
  };
  const auto a = cache.get(8, make(8));
  const auto b = cache.get(8, make(8));
  const auto c = cache.get(16, make(16));
  CHECK(a.get() == b.get());  // the same object, not a copy
  CHECK(a.get() != c.get());
  CHECK(builds == 2);
  CHECK(cache.builds() == 2);
  CHECK(cache.live_tiles() == 2);
  CHECK(cache.live_bytes() == (8 + 16) * sizeof(int));
}

TEST_CASE("tile_cache: a tile no one holds is released, and rebuilt when asked again") {
  hush::tile_cache<int, fake_tile> cache;
  {
    const auto a = cache.get(4, [] { return fake_tile(4); });
    CHECK(cache.live_tiles() == 1);
  }
  CHECK(cache.live_tiles() == 0);
  CHECK(cache.live_bytes() == 0);
  const auto again = cache.get(4, [] { return fake_tile(4); });
  CHECK(again->values.size() == 4);
  CHECK(cache.builds() == 2);
}

TEST_CASE("tile_cache: threads asking for the same key all receive one tile") {
  hush::tile_cache<int, fake_tile> cache;
  std::atomic<int> builds{0};
  std::vector<std::shared_ptr<const fake_tile>> got(8);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < got.size(); ++t)
    threads.emplace_back([&, t] {
      got[t] = cache.get(32, [&] {
        ++builds;
        return fake_tile(32);
      });
    });
  for (auto& th : threads) th.join();
  for (const auto& g : got) CHECK(g.get() == got[0].get());
  CHECK(builds.load() >= 1);
  CHECK(cache.builds() == 1);  // extra builds of a racing thread are dropped, not stored
}
