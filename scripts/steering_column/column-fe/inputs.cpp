// SPDX-License-Identifier: MIT
#include "inputs.hpp"

#include <stdexcept>

namespace cfe {

const std::vector<InputSpec>& input_specs() {
  using K = InputKind;
  static const std::vector<InputSpec> specs = [] {
    std::vector<InputSpec> s = {
        {"column_frame_E", 205000, K::positive},  {"hub_E", 200000, K::positive},
        {"housing_E", 71000, K::positive},        {"heatsink_E", 69000, K::positive},
        {"wheel_frame_E", 45000, K::positive},    {"wheel_cover_E", 200, K::positive},
        {"column_frame_nu", 0.29, K::poisson},    {"hub_nu", 0.30, K::poisson},
        {"housing_nu", 0.33, K::poisson},         {"heatsink_nu", 0.33, K::poisson},
        {"wheel_frame_nu", 0.35, K::poisson},     {"wheel_cover_nu", 0.45, K::poisson},
        {"column_frame_rho", 7.85e-9, K::positive}, {"hub_rho", 7.85e-9, K::positive},
        {"housing_rho", 2.70e-9, K::positive},    {"heatsink_rho", 2.70e-9, K::positive},
        {"wheel_frame_rho", 1.77e-9, K::positive}, {"wheel_cover_rho", 1.00e-9, K::positive},
        {"column_tube_thickness", 2.0, K::positive}, {"housing_thickness", 4.0, K::positive},
        {"ecu_bracket_thickness", 3.2, K::positive}, {"tilt_bracket_thickness", 2.6, K::positive},
        {"heatsink_thickness", 5.0, K::positive}, {"spoke_thickness", 3.0, K::positive},
        {"wheel_cover_thickness", 5.5, K::positive}};
    const double bush[4][3] = {{2000, 3000, 3000}, {2000, 3000, 3000}, {1000, 1500, 200}, {1000, 1500, 200}};
    for (int b = 0; b < 4; ++b) {
      const std::string p = "bush" + std::to_string(b + 1);
      s.push_back({p + "_ka", bush[b][0], K::positive});
      s.push_back({p + "_kl", bush[b][1], K::positive});
      s.push_back({p + "_kv", bush[b][2], K::positive});
    }
    for (int b = 1; b <= 4; ++b) {
      s.push_back({"bearing" + std::to_string(b) + "_kl", 15000, K::positive});
      s.push_back({"bearing" + std::to_string(b) + "_kv", 15000, K::positive});
    }
    s.push_back({"tilt_lock_k", 200, K::positive});
    s.push_back({"airbag_stiffness", 1000, K::positive});
    return s;
  }();
  return specs;
}

const InputSpec* find_input(const std::string& name) {
  for (const auto& s : input_specs())
    if (s.name == name) return &s;
  return nullptr;
}

double Inputs::operator()(const std::string& name) const {
  auto it = values.find(name);
  if (it == values.end()) throw std::out_of_range("smi-column-fe: input '" + name + "' is not set");
  return it->second;
}

void Inputs::set(const std::string& name, double value) {
  if (!find_input(name)) throw std::invalid_argument("smi-column-fe: '" + name + "' is not an input of the model");
  values[name] = value;
}

Inputs nominal_inputs(Airbag airbag, int refinement) {
  Inputs in;
  in.airbag = airbag;
  in.refinement = refinement;
  for (const auto& s : input_specs()) in.values[s.name] = s.nominal;
  return in;
}

const char* airbag_name(Airbag a) { return a == Airbag::rigid ? "rigid" : "spring"; }

}  // namespace cfe
