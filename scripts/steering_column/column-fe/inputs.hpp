// SPDX-License-Identifier: MIT
#pragma once
// The model's inputs (spec §2): the 46 named inputs, airbag_stiffness, the airbag variant and the
// mesh refinement. Kept as a name -> value map because decks, tests and the data generator all
// address inputs by their spec names.
#include <map>
#include <string>
#include <vector>

namespace cfe {

enum class Airbag { rigid, spring };

/// What a value must satisfy besides being finite (§9).
enum class InputKind { positive, poisson };

struct InputSpec {
  std::string name;
  double nominal;
  InputKind kind;
};

/// The 46 inputs of §2 in table order, followed by airbag_stiffness (index 46).
const std::vector<InputSpec>& input_specs();
/// The spec of `name`, or nullptr when the name is not an input.
const InputSpec* find_input(const std::string& name);

struct Inputs {
  Airbag airbag = Airbag::rigid;
  int refinement = 1;
  std::map<std::string, double> values;

  /// The value of `name`; throws std::out_of_range naming the key when it is absent.
  double operator()(const std::string& name) const;
  void set(const std::string& name, double value);
};

/// Every input at its nominal value (§2), for the given variant and refinement.
Inputs nominal_inputs(Airbag airbag, int refinement = 1);

const char* airbag_name(Airbag a);  // "rigid" / "spring"

}  // namespace cfe
