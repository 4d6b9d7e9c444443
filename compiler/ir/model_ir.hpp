// The model IR: what a .mdl file says, resolved into plain data.
//
// The IR is independent of GiNaC: expressions are kept as a small AST (ir::Expr) so that the front end,
// the model writer (extension operators write a readable .mdl back) and the symbolic stage can each use it.
// Numbers keep their literal text; the symbolic stage turns them into exact rationals.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace mbgen::ir {

struct SourceLoc {
  int line = 0;    // 1-based; 0 = not from a file (e.g. added by an extension operator)
  int column = 0;  // 1-based
};

// Expression AST over parameter names.
struct Expr {
  enum class Kind {
    Number,  // text = literal as written ("0.127", "60e6", "3")
    Symbol,  // text = parameter name, or the constant "pi"
    Add,     // args[0] + args[1] + ... (two or more terms; the parser writes `a - b` as a term Neg(b))
    Sub,     // args[0] - args[1] (built by code; the parser does not make it)
    Mul,     // args[0] * args[1] * ... (two or more factors)
    Div,     // args[0] / args[1]
    Pow,     // args[0] ^ args[1]
    Neg,     // -args[0]
    Call,    // text = function name (sqrt, sin, cos), args = arguments
  };
  Kind kind = Kind::Number;
  std::string text;
  std::vector<Expr> args;
  SourceLoc loc;

  static Expr number(std::string literal, SourceLoc l = {});
  static Expr symbol(std::string name, SourceLoc l = {});
  static Expr binary(Kind k, Expr a, Expr b, SourceLoc l = {});
  static Expr sum(std::vector<Expr> terms, SourceLoc l = {});
  static Expr product(std::vector<Expr> factors, SourceLoc l = {});
  static Expr negate(Expr a, SourceLoc l = {});
  static Expr call(std::string fn, std::vector<Expr> a, SourceLoc l = {});

  bool is_number() const { return kind == Kind::Number; }
  bool is_symbol() const { return kind == Kind::Symbol; }
};

// A number literal's value as the nearest double (±infinity or 0 beyond the double range), and whether it is
// exactly zero (every digit of its mantissa is 0). Neither throws for a literal the lexer accepted.
double literal_value(const std::string& literal);
bool is_zero_literal(const std::string& literal);

// How deeply an expression may nest (levels of operators, parentheses and calls, with the derived parameters it
// uses written out): the parser and the checks reject deeper ones, so that recursive passes over expressions
// (checks, GiNaC, printers) stay far from the end of the stack. Flat sums and products do not count per term.
inline constexpr int kMaxExpressionDepth = 256;

// Infix text with the fewest parentheses that keep the meaning; re-parses to an equal tree.
std::string to_string(const Expr& e);
// Names of the symbols an expression uses (without "pi"), in first-use order, each once.
std::vector<std::string> symbols_of(const Expr& e);

using Vec3 = std::array<Expr, 3>;

enum class Role { Known, Estimate, Fixed };
const char* to_string(Role r);

struct Parameter {
  std::string name;
  Expr value;            // a number, or an expression of other parameters (then `derived` is true)
  bool derived = false;  // defined as an expression of other parameters: not a free parameter
  std::string unit;      // free text, e.g. "N/m"; empty if not given
  Role role = Role::Known;
  std::optional<Expr> lower, upper;  // bounds (numbers or expressions), if given
  std::string comment;               // trailing comment of the declaration, kept for the writer
  SourceLoc loc;
};

// Generalized coordinates a body may have, in this fixed order.
enum class Dof { X = 0, Y, Z, RX, RY, RZ };
const char* to_string(Dof d);  // "x", "y", "z", "rx", "ry", "rz"

struct Ground {
  std::string name;
  SourceLoc loc;
};

struct Body {
  std::string name;
  Expr mass;
  // Inertia tensor about the centre of mass in the global frame: xx, yy, zz, xy, xz, yz.
  // Absent products are zero; an absent inertia statement means all zero.
  std::array<std::optional<Expr>, 6> inertia;
  Vec3 position;          // centre of mass at the nominal configuration (global frame)
  std::vector<Dof> dofs;  // its generalized coordinates, in the order written
  SourceLoc loc;
};

// A place on a body or a ground. `frame` names a body or a ground.
struct Attachment {
  std::string frame;
  Vec3 point;              // global coordinates at the nominal configuration
  bool has_point = false;  // written with `at`; otherwise `point` is the body's centre of mass (ground: origin)
  SourceLoc loc;
};

// A direction: an axis name ("x", "y", "z") or a vector (normalized by the symbolic stage).
struct Direction {
  std::string axis;  // "x", "y", "z", or empty when `vector` is used
  Vec3 vector;       // always filled (unit vector for axis names)
  SourceLoc loc;
};

enum class ElementKind {
  Spring,     // one-dimensional: force k*elongation along `direction`
  Spring3,    // three-dimensional: per global axis x, y, z stiffness and damping
  Torsion,    // rotational: moment k*(relative rotation about `direction`)
};
const char* to_string(ElementKind k);  // "spring", "spring3", "torsion"

struct Element {
  std::string name;
  ElementKind kind = ElementKind::Spring;
  Attachment a, b;            // from a to b
  Direction direction;        // Spring and Torsion only
  std::vector<Expr> stiffness;  // 1 entry (Spring, Torsion) or 3 (Spring3: x, y, z)
  std::vector<Expr> damping;    // same count as stiffness; may be empty = no damping
  SourceLoc loc;
};

// A body spinning about one of its principal axes at `speed` (rev/s): gyroscopic coupling.
struct Spin {
  std::string body;
  std::string axis;  // "x", "y" or "z"
  Expr speed;        // rev/s; angular speed is 2*pi*speed
  SourceLoc loc;
};

enum class InputKind { Force, Moment };
enum class OutputKind { Displacement, Velocity, Acceleration };
const char* to_string(InputKind k);   // "force", "moment"
const char* to_string(OutputKind k);  // "displacement", "velocity", "acceleration"

struct Input {
  std::string name;
  InputKind kind = InputKind::Force;
  Attachment at;  // a Moment ignores at.point
  Direction direction;
  // What the recorded input reads per unit of the applied force or moment (a force transducer's calibration, or -1
  // for its sign), if given: the input map's column is divided by it. Absent means 1.
  std::optional<Expr> gain;
  SourceLoc loc;
};

struct Output {
  std::string name;
  OutputKind kind = OutputKind::Displacement;
  Attachment at;
  Direction direction;
  SourceLoc loc;
};

// Signal conditioning between a sensor and the recorded output: the output records its sensor's reading passed
// through its filters, in declaration order (docs/language.md, "Filters").
enum class FilterKind {
  Lowpass2,   // wc^2 / (s^2 + 2 zeta wc s + wc^2): an electrical low-pass, no zero
  Highpass1,  // s / (s + wc): AC coupling
  Highpass2,  // s^2 / (s^2 + 2 zeta wc s + wc^2): a charge amplifier's or a second-order AC coupling
  Delay,      // exp(-s tau), as `sections` second-order Pade sections of tau / sections each
  Gain,       // a constant factor: a sensor's calibration (sensitivity) error, or its polarity (-1)
};
const char* to_string(FilterKind k);  // "lowpass2", "highpass1", "highpass2", "delay", "gain"

struct Filter {
  std::string name;
  std::string output;           // the output it conditions
  FilterKind kind = FilterKind::Lowpass2;
  std::optional<Expr> cutoff;   // Hz: Lowpass2, Highpass1, Highpass2
  std::optional<Expr> damping;  // damping ratio: Lowpass2, Highpass2
  std::optional<Expr> time;     // s: Delay
  std::optional<Expr> factor;   // Gain (not zero)
  int sections = 1;             // Delay only
  SourceLoc loc;
};

// A model as the front end describes it: what the .mdl says, checked and with source locations. Named apart from
// the derived equations (symbolic::SymbolicModel) and the numeric model the runtime evaluates (mbgen::Model).
struct ModelIr {
  std::string name;  // from `model NAME`
  SourceLoc name_loc;  // of NAME in the `model` statement (none when the name comes from the file name)
  std::string file;  // path it was read from ("-" for stdin, empty if built in code)
  std::vector<Parameter> parameters;
  std::vector<Ground> grounds;
  std::vector<Body> bodies;
  std::vector<Element> elements;
  std::vector<Spin> spins;
  std::vector<Input> inputs;
  std::vector<Output> outputs;
  std::vector<Filter> filters;

  const Parameter* find_parameter(const std::string& n) const;
  const Body* find_body(const std::string& n) const;
  const Ground* find_ground(const std::string& n) const;
  bool is_ground(const std::string& n) const { return find_ground(n) != nullptr; }
};

}  // namespace mbgen::ir
