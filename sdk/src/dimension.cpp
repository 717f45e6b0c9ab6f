#include <mechgraph/dimension.hpp>

#include <string>
#include <utility>
#include <vector>

namespace mechgraph {
namespace {

struct Base {
  const char* symbol;
  const char* name;
  int exponent;
};

std::vector<Base> bases_of(const Dimension& d) {
  return {{"kg", "mass", d.mass}, {"m", "length", d.length}, {"s", "time", d.time},
          {"rad", "angle", d.angle}, {"K", "temperature", d.temperature}};
}

std::string join(const Dimension& d, bool names) {
  std::string num, den;
  for (const Base& b : bases_of(d)) {
    if (b.exponent == 0) continue;
    std::string& side = b.exponent > 0 ? num : den;
    const int e = b.exponent > 0 ? b.exponent : -b.exponent;
    if (!side.empty()) side += "*";
    side += names ? b.name : b.symbol;
    if (e != 1) side += "^" + std::to_string(e);
  }
  if (num.empty() && den.empty()) return names ? "dimensionless" : "1";
  if (den.empty()) return num;
  return (num.empty() ? std::string("1") : num) + "/" + den;
}

}  // namespace

std::string Dimension::si_unit() const {
  // Derived names engineers read faster than base-unit products.
  static const std::pair<Dimension, const char*> named[] = {
      {dim::force, "N"}, {dim::stress, "Pa"}, {dim::stiffness, "N/m"}, {dim::force * dim::length, "N*m"},
      {dim::force * dim::time / dim::length, "N*s/m"}};
  for (const auto& [d, name] : named)
    if (d == *this) return name;
  return join(*this, false);
}

std::string Dimension::describe() const { return join(*this, true); }

}  // namespace mechgraph
