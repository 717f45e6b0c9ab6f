#pragma once
// Physical dimension as a vector of exponents over the SI base quantities mechgraph uses:
// length (m), mass (kg), time (s), temperature (K), plus plane angle (rad) kept as its own
// "base" so that a scene cannot feed an angle where a length is expected (angle is
// dimensionless in strict SI; treating it as a dimension catches real mistakes).
#include <cstdint>
#include <string>

namespace mechgraph {

struct Dimension {
  std::int8_t length = 0;
  std::int8_t mass = 0;
  std::int8_t time = 0;
  std::int8_t angle = 0;
  std::int8_t temperature = 0;

  friend constexpr bool operator==(const Dimension&, const Dimension&) = default;

  constexpr Dimension operator*(const Dimension& o) const {
    return {static_cast<std::int8_t>(length + o.length), static_cast<std::int8_t>(mass + o.mass),
            static_cast<std::int8_t>(time + o.time), static_cast<std::int8_t>(angle + o.angle),
            static_cast<std::int8_t>(temperature + o.temperature)};
  }
  constexpr Dimension operator/(const Dimension& o) const {
    return {static_cast<std::int8_t>(length - o.length), static_cast<std::int8_t>(mass - o.mass),
            static_cast<std::int8_t>(time - o.time), static_cast<std::int8_t>(angle - o.angle),
            static_cast<std::int8_t>(temperature - o.temperature)};
  }
  constexpr Dimension pow(int n) const {
    return {static_cast<std::int8_t>(length * n), static_cast<std::int8_t>(mass * n),
            static_cast<std::int8_t>(time * n), static_cast<std::int8_t>(angle * n),
            static_cast<std::int8_t>(temperature * n)};
  }
  constexpr bool dimensionless() const { return *this == Dimension{}; }

  /// SI unit text, e.g. "m", "m^2*s", "kg/s^2", "rad/s"; "1" when dimensionless.
  std::string si_unit() const;
  /// Human description, e.g. "length", "angle", "length^2*time".
  std::string describe() const;
};

/// Named dimensions plugin authors use in parameter and port specs.
namespace dim {
inline constexpr Dimension none{};
inline constexpr Dimension length{1, 0, 0, 0, 0};
inline constexpr Dimension mass{0, 1, 0, 0, 0};
inline constexpr Dimension time{0, 0, 1, 0, 0};
inline constexpr Dimension angle{0, 0, 0, 1, 0};
inline constexpr Dimension temperature{0, 0, 0, 0, 1};
inline constexpr Dimension area = length * length;
inline constexpr Dimension velocity = length / time;
inline constexpr Dimension acceleration = velocity / time;
inline constexpr Dimension angular_speed = angle / time;
inline constexpr Dimension frequency = none / time;
inline constexpr Dimension force = mass * acceleration;
inline constexpr Dimension stress = force / area;
inline constexpr Dimension stiffness = force / length;
inline constexpr Dimension density = mass / (area * length);
inline constexpr Dimension moment_of_inertia = mass * area;
inline constexpr Dimension per_kelvin = none / temperature;
}  // namespace dim

}  // namespace mechgraph
