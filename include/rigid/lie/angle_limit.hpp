#pragma once

/// The largest rotation angle the groups accept.

namespace rigid {

/// The largest |angle| (rad) the rotation groups accept (Euler angles, axis-angle, the length
/// of a rotation vector, an interpolated turn). Doubles near 1e15 are spaced 0.125 apart, a
/// fiftieth of a turn: beyond, rounding has lost which fraction of a turn the angle meant, so
/// a larger angle is refused rather than turned into an arbitrary rotation (and an angle whose
/// square overflows, near 1e154, into NaN).
inline constexpr double kMaxAngle = 1e15;

}  // namespace rigid
