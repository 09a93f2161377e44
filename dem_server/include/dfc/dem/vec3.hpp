#pragma once
// Vec3: the 3-vector of the DEM hot loops. A plain aggregate of three doubles
// (24 bytes, no padding) so that std::vector<Vec3> is a dense x,y,z stream
// that one cache line serves per particle, and every operation inlines.
#include <cmath>

namespace dfc::dem {

struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  constexpr Vec3& operator+=(const Vec3& o) noexcept { x += o.x; y += o.y; z += o.z; return *this; }
  constexpr Vec3& operator-=(const Vec3& o) noexcept { x -= o.x; y -= o.y; z -= o.z; return *this; }
  constexpr Vec3& operator*=(double s) noexcept { x *= s; y *= s; z *= s; return *this; }
  friend constexpr bool operator==(const Vec3&, const Vec3&) = default;
};

[[nodiscard]] constexpr Vec3 operator+(Vec3 a, const Vec3& b) noexcept { return a += b; }
[[nodiscard]] constexpr Vec3 operator-(Vec3 a, const Vec3& b) noexcept { return a -= b; }
[[nodiscard]] constexpr Vec3 operator-(const Vec3& a) noexcept { return {-a.x, -a.y, -a.z}; }
[[nodiscard]] constexpr Vec3 operator*(double s, Vec3 a) noexcept { return a *= s; }
[[nodiscard]] constexpr Vec3 operator*(Vec3 a, double s) noexcept { return a *= s; }
[[nodiscard]] constexpr double dot(const Vec3& a, const Vec3& b) noexcept { return a.x * b.x + a.y * b.y + a.z * b.z; }
[[nodiscard]] constexpr Vec3 cross(const Vec3& a, const Vec3& b) noexcept {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
[[nodiscard]] constexpr double norm2(const Vec3& a) noexcept { return dot(a, a); }
[[nodiscard]] inline double norm(const Vec3& a) noexcept { return std::sqrt(dot(a, a)); }
[[nodiscard]] inline bool is_finite(const Vec3& a) noexcept { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

}  // namespace dfc::dem
