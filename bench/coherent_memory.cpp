// hush — the speed-vs-error benchmark: the memory-bound reference pass of coherent noise's
// rows (coherent_cases.cpp). It moves the bytes a coherent-noise frame must move, with as
// little arithmetic as that allows: reads this frame's depth, velocity and object ids,
// gathers the previous frame's depth, ids and history at the four bilinear taps, blends the
// history bilinearly, and writes the output, the new history, the depth and id copies and a
// flag byte. Highway, dynamically dispatched like hush::simd (so `simd AVX2` pins it too).
// Its result is not coherent noise; only its time matters.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "coherent_memory.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "coherent_memory.hpp"

HWY_BEFORE_NAMESPACE();
namespace hush_bench {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void memory_pass(const memory_job& j) {
  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  const hn::RebindToUnsigned<decltype(df)> du;
  const hn::Rebind<std::uint8_t, decltype(di)> d8;
  const std::size_t lanes = hn::Lanes(df), w = j.width;
  const auto max_u = hn::Set(df, float(j.width - 1)), max_v = hn::Set(df, float(j.height - 1));
  const auto last_i = hn::Set(df, float(j.width - 2)), last_j = hn::Set(df, float(j.height - 2));
  const auto zero = hn::Zero(df), one = hn::Set(df, 1.0f);
  for (std::size_t y = 0; y < j.height; ++y)
    for (std::size_t x = 0; x + lanes <= w; x += lanes) {
      const std::size_t p = y * w + x;
      const auto depth = hn::LoadU(df, j.depth + p);
      decltype(hn::Zero(df)) mx, my, mz;
      hn::LoadInterleaved3(df, j.motion + 3 * p, mx, my, mz);
      const auto id = hn::LoadU(du, j.ids + p);
      const auto u = hn::Min(hn::Max(hn::Sub(hn::Iota(df, float(x)), mx), zero), max_u);
      const auto v = hn::Min(hn::Max(hn::Sub(hn::Set(df, float(y)), my), zero), max_v);
      const auto i0 = hn::Min(hn::Floor(u), last_i), j0 = hn::Min(hn::Floor(v), last_j);
      const auto tx = hn::Sub(u, i0), ty = hn::Sub(v, j0);
      const auto a = hn::Sub(one, tx), b = hn::Sub(one, ty);
      const auto t00 =
          hn::Add(hn::Mul(hn::ConvertTo(di, j0), hn::Set(di, int(w))), hn::ConvertTo(di, i0));
      const auto t10 = hn::Add(t00, hn::Set(di, 1));
      const auto t01 = hn::Add(t00, hn::Set(di, int(w)));
      const auto t11 = hn::Add(t01, hn::Set(di, 1));
      // With `contiguous`, vectors whose taps are adjacent columns of one row load them
      // (as hush's kernel does), the others gather; without, every tap is gathered.
      const std::int32_t first = hn::GetLane(t00);
      const bool loads = j.contiguous &&
                         hn::AllTrue(di, hn::Eq(hn::Sub(t00, hn::Iota(di, 0)), hn::Set(di, first)));
      const std::size_t base = static_cast<std::size_t>(first);
      auto tap = [&](auto d, const auto* plane, const decltype(t00)& t, std::size_t offset) {
        return loads ? hn::LoadU(d, plane + base + offset) : hn::GatherIndex(d, plane, t);
      };
      auto bilinear = [&](const float* plane) {
        return hn::MulAdd(hn::Mul(tx, ty), tap(df, plane, t11, w + 1),
                          hn::MulAdd(hn::Mul(a, ty), tap(df, plane, t01, w),
                                     hn::MulAdd(hn::Mul(tx, b), tap(df, plane, t10, 1),
                                                hn::Mul(hn::Mul(a, b), tap(df, plane, t00, 0)))));
      };
      const auto same = hn::And(
          hn::And(hn::Eq(tap(du, j.ref_ids, t00, 0), id), hn::Eq(tap(du, j.ref_ids, t10, 1), id)),
          hn::And(hn::Eq(tap(du, j.ref_ids, t01, w), id),
                  hn::Eq(tap(du, j.ref_ids, t11, w + 1), id)));
      const auto near = hn::Lt(hn::Abs(hn::Sub(bilinear(j.ref_depth), hn::Sub(depth, mz))),
                               hn::Mul(depth, hn::Set(df, 0.02f)));
      const auto keep = hn::And(hn::RebindMask(df, same), near);
      const auto value = hn::IfThenElse(keep, bilinear(j.history), depth);
      hn::StoreU(value, df, j.out + p);
      hn::StoreU(value, df, j.next_history + p);
      hn::StoreU(depth, df, j.depth_copy + p);
      hn::StoreU(id, du, j.ids_copy + p);
      hn::StoreU(hn::DemoteTo(d8, hn::IfThenElseZero(hn::RebindMask(di, keep), hn::Set(di, 1))), d8,
                 j.flags + p);
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace hush_bench
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace hush_bench {
HWY_EXPORT(memory_pass);
void coherent_memory_pass(const memory_job& j) { HWY_DYNAMIC_DISPATCH(memory_pass)(j); }
}  // namespace hush_bench
#endif
