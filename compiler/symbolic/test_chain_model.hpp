// A model of machine scale for tests and benchmarks: a chain of N rigid bodies with all six coordinates, each
// held to the previous one (the first to the ground) by three three-dimensional spring-dampers at the corners of
// a triangle; one force input on the last body, two displacement outputs (issue 14's measured case).
//
// Every body and every connection has its own values, deterministic and varied (no two bodies alike), so no
// symmetry makes the chain easier than a real machine's (symmetry brings repeated poles and cancellations).
// Masses, stiffnesses and dampings are parameters to estimate (3 per body); inertias and geometry are numbers.
#pragma once

#include <string>

namespace mbgen::symbolic::test {

inline std::string chain_model_text(int bodies) {
  // Decimal text of an integer scaled by 10^-digits: exact in the model language.
  auto decimal = [](long value, int digits) {
    const bool negative = value < 0;
    std::string t = std::to_string(negative ? -value : value);
    while (static_cast<int>(t.size()) <= digits) t.insert(t.begin(), '0');
    if (digits > 0) t.insert(t.end() - digits, '.');
    return negative ? "-" + t : t;
  };
  std::string text = "# A chain of " + std::to_string(bodies) +
                     " rigid bodies, each held to the previous one by three three-dimensional spring-dampers.\n"
                     "model chain" + std::to_string(bodies) + "\n\nground base\n";
  for (int i = 1; i <= bodies; ++i) {
    const std::string n = std::to_string(i);
    const int v = (i * 37) % 23;  // a deterministic spread of values
    text += "param m" + n + " = " + decimal(1500 + 97 * v, 2) + " \"kg\" estimate in [0, 1000]\n";
    text += "param k" + n + " = " + decimal(40 + 3 * ((i * 11) % 17), 0) + "e6 \"N/m\" estimate in [0, 1e10]\n";
    text += "param c" + n + " = " + decimal(500 + 41 * ((i * 13) % 19), 0) + " \"N s/m\" estimate in [0, 1e6]\n";
  }
  for (int i = 1; i <= bodies; ++i) {
    const std::string n = std::to_string(i), z = decimal(500L * i, 3);
    const int v = (i * 29) % 31;
    text += "\nbody b" + n + " {\n  mass m" + n + "\n  inertia " + decimal(210 + 7 * v, 3) + ", " +
            decimal(230 + 5 * v, 3) + ", " + decimal(90 + 3 * v, 3) + ", " + decimal(v, 4) + ", 0, " +
            decimal(2 * v, 4) + "\n  at (0, 0, " + z + ")\n  dof x y z rx ry rz\n}\n";
  }
  // Triangle corners (x, y) in mm; the springs sit halfway between the bodies (250 mm below body i).
  const int corner[3][2] = {{-120, -70}, {120, -70}, {0, 140}};
  for (int i = 1; i <= bodies; ++i) {
    const std::string n = std::to_string(i), from = i == 1 ? "base" : "b" + std::to_string(i - 1);
    const std::string z = decimal(500L * i - 250, 3);
    for (int c = 0; c < 3; ++c) {
      const std::string at = "(" + decimal(corner[c][0] + (i % 5), 3) + ", " + decimal(corner[c][1], 3) + ", " + z + ")";
      const std::string kz = c == 0 ? "2*k" + n : c == 1 ? "3*k" + n + "/2" : "5*k" + n + "/2";
      text += "\nspring3 s" + n + "_" + std::to_string(c + 1) + " {\n  from " + from + " at " + at + "\n  to b" + n +
              " at " + at + "\n  stiffness k" + n + ", " + decimal(8 + c, 1) + "*k" + n + ", " + kz +
              "\n  damping c" + n + ", c" + n + ", " + std::to_string(c + 2) + "*c" + n + "\n}\n";
    }
  }
  const std::string last = "b" + std::to_string(bodies);
  text += "\ninput F force on " + last + " at (0.05, 0, " + decimal(500L * bodies, 3) + ") along x\n";
  text += "output x_tip displacement of " + last + " at (0, 0.03, " + decimal(500L * bodies + 100, 3) + ") along x\n";
  text += "output y_mid displacement of b" + std::to_string((bodies + 1) / 2) + " at (0.02, 0, " +
          decimal(500L * ((bodies + 1) / 2), 3) + ") along y\n";
  return text;
}

}  // namespace mbgen::symbolic::test
