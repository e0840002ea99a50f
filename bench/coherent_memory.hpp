// hush — the speed-vs-error benchmark: the memory-bound reference pass of the coherent-noise
// rows (coherent_memory.cpp says what it moves).
#ifndef HUSH_BENCH_COHERENT_MEMORY_HPP
#define HUSH_BENCH_COHERENT_MEMORY_HPP

#include <cstddef>
#include <cstdint>

namespace hush_bench {

// Packed planes of width x height pixels (motion: 3 floats per pixel); width a multiple of
// the widest vector (16 floats) and >= 2, height >= 2.
struct memory_job {
  std::size_t width = 0, height = 0;
  const float* depth = nullptr;
  const float* motion = nullptr;
  const std::uint32_t* ids = nullptr;
  const float* ref_depth = nullptr;
  const std::uint32_t* ref_ids = nullptr;
  const float* history = nullptr;
  float* next_history = nullptr;
  float* out = nullptr;
  float* depth_copy = nullptr;
  std::uint32_t* ids_copy = nullptr;
  std::uint8_t* flags = nullptr;
  // Load the taps of vectors whose taps are adjacent columns of one row instead of gathering
  // them (what hush's kernel does); false: gather every tap.
  bool contiguous = false;
};

// One pass over the frame, on the best SIMD target (or the one pinned for the run).
void coherent_memory_pass(const memory_job& job);

}  // namespace hush_bench

#endif  // HUSH_BENCH_COHERENT_MEMORY_HPP
