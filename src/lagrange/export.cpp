// Code export: the equations of motion of a System as straight-line C++ or Python.
//
// Each exported function is one tape (detail::TapeBuilder: shared subexpressions, value
// numbering, the engine's operation order) printed instruction by instruction, one local per
// instruction. Printing the tape rather than the expressions keeps the sharing, and makes the
// exported numbers the engine's own: the same operations on the same operands in the same
// order (binary powering for integer powers included).
#include "rigid/lagrange/export.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"
#include "detail/derivatives.hpp"
#include "detail/recursive.hpp"
#include "detail/symbolic.hpp"
#include "detail/symbolic_lock.hpp"
#include "detail/system_impl.hpp"
#include "detail/tape.hpp"

namespace rigid::lagrange {
namespace {

using detail::Instruction;
using detail::Op;
using detail::Tape;

// The compiled model of a System. System's public header declares no friend for the other
// files of this module; a workspace records the model it belongs to, which is this one.
const System::Impl& impl_of(const System& system) {
  Workspace w = system.make_workspace();
  return *Workspace::Access::impl(w)->owner;
}

// ----------------------------------------------------------------------------------------
// names
//
// Every name of the user's that the export writes as an identifier (a parameter: a C++
// struct member and designated initializer, a Python keyword argument; the C++ namespace)
// passes through export_identifiers(), one rule for both languages:
//   1. characters other than letters, digits and '_' become '_'; an empty name, or one
//      starting with a digit, takes "model_" in front (only a file name can need this);
//   2. a name starting with '_' takes a 'p' in front: such names are the implementation's
//      (C and C++ reserve "__x" and "_X" everywhere, "_x" at namespace scope; the Python
//      module's own names start with '_');
//   3. a name that is reserved (below) or already a name of another parameter takes a '_'
//      at its end, again until it is neither.
// The coordinates' and constraints' names are written as string literals and in comments
// only, so they keep their names.

// C++20 keywords and alternative tokens, identifiers with a special meaning, keywords of the
// technical specifications (transactional memory, reflection), C11/C23 keywords without a
// leading '_' and GNU's `typeof` (a keyword of g++ and clang++ in their default gnu++ modes).
constexpr std::string_view kCppKeywords[] = {
    "alignas", "alignof", "and", "and_eq", "asm", "atomic_cancel", "atomic_commit",
    "atomic_noexcept", "auto", "bitand", "bitor", "bool", "break", "case", "catch", "char",
    "char8_t", "char16_t", "char32_t", "class", "compl", "concept", "const", "consteval",
    "constexpr", "constinit", "const_cast", "continue", "co_await", "co_return", "co_yield",
    "decltype", "default", "delete", "do", "double", "dynamic_cast", "else", "enum", "explicit",
    "export", "extern", "false", "float", "for", "friend", "goto", "if", "inline", "int", "long",
    "mutable", "namespace", "new", "noexcept", "not", "not_eq", "nullptr", "operator", "or",
    "or_eq", "private", "protected", "public", "reflexpr", "register", "reinterpret_cast",
    "requires", "return", "short", "signed", "sizeof", "static", "static_assert", "static_cast",
    "struct", "switch", "synchronized", "template", "this", "thread_local", "throw", "true", "try",
    "typedef", "typeid", "typename", "union", "unsigned", "using", "virtual", "void", "volatile",
    "wchar_t", "while", "xor", "xor_eq", "final", "override", "import", "module",
    "transaction_safe", "transaction_safe_dynamic", "restrict", "typeof", "typeof_unqual"};

// Object-like macros a member could meet: the system names GCC and Clang predefine on Linux in
// their gnu modes (`echo | g++ -std=gnu++20 -dM -E -x c++ -`: linux, unix; i386 with -m32;
// mips, sparc on those targets; sun, vax, m68k, hppa on others), and those <cmath> defines
// with glibc (`echo '#include <cmath>' | g++ -dM -E -x c++ -`, the names without a leading
// '_'; the M_ constants are kMathConstants below). A function-like macro expands only before
// '(', which never follows a parameter's name in the exported code.
constexpr std::string_view kCppMacros[] = {
    "linux", "unix", "i386", "mips", "sparc", "sun", "vax", "m68k", "hppa", "errno", "assert",
    "math_errhandling", "NULL", "NAN", "INFINITY", "HUGE_VAL", "HUGE_VALF", "HUGE_VALL",
    "HUGE_VAL_F32", "HUGE_VAL_F64", "HUGE_VAL_F128", "HUGE_VAL_F32X", "HUGE_VAL_F64X", "SNAN",
    "SNANF", "SNANL", "SNANF32", "SNANF64", "SNANF128", "SNANF32X", "SNANF64X", "MAXFLOAT",
    "EDOM", "ERANGE", "EILSEQ", "MATH_ERRNO", "MATH_ERREXCEPT", "FP_NAN", "FP_INFINITE",
    "FP_ZERO", "FP_SUBNORMAL", "FP_NORMAL", "FP_ILOGB0", "FP_ILOGBNAN", "FP_LLOGB0",
    "FP_LLOGBNAN", "FP_FAST_FMA", "FP_FAST_FMAF", "FP_FAST_FMAL", "FP_INT_UPWARD",
    "FP_INT_DOWNWARD", "FP_INT_TOWARDZERO", "FP_INT_TONEARESTFROMZERO", "FP_INT_TONEAREST",
    "EXIT_SUCCESS", "EXIT_FAILURE", "RAND_MAX", "MB_CUR_MAX", "BIG_ENDIAN", "LITTLE_ENDIAN",
    "PDP_ENDIAN", "BYTE_ORDER", "FD_SETSIZE", "NFDBITS", "WNOHANG", "WUNTRACED", "WSTOPPED",
    "WEXITED", "WCONTINUED", "WNOWAIT"};

// glibc's M_ constants, each with the suffixes of its float types (M_PI, M_PIf, M_PIl, ...).
constexpr std::string_view kMathConstants[] = {"E",     "LOG2E", "LOG10E", "LN2",      "LN10",
                                               "PI",    "PI_2",  "PI_4",   "1_PI",     "2_PI",
                                               "2_SQRTPI", "SQRT2", "SQRT1_2"};

// The suffixes of the C library's float types: double, float, long double, _FloatN, _FloatNx.
constexpr std::string_view kFloatSuffixes[] = {"",    "f",    "l",    "f16",  "f32",
                                               "f64", "f128", "f32x", "f64x", "f128x"};

// The functions of <math.h> (C23 and glibc's), each also with the suffixes above and glibc's
// reentrant "_r": at global scope where the namespace is, they clash with it.
constexpr std::string_view kMathFunctions[] = {
    "acos", "asin", "atan", "atan2", "cos", "sin", "tan", "acosh", "asinh", "atanh", "cosh",
    "sinh", "tanh", "acospi", "asinpi", "atanpi", "atan2pi", "cospi", "sinpi", "tanpi", "exp",
    "exp2", "exp10", "expm1", "exp2m1", "exp10m1", "frexp", "ilogb", "llogb", "ldexp", "log",
    "log10", "log2", "log1p", "logp1", "log2p1", "log10p1", "logb", "modf", "scalbn", "scalbln",
    "scalb", "cbrt", "fabs", "hypot", "pow", "pown", "powr", "rootn", "rsqrt", "compoundn",
    "sqrt", "erf", "erfc", "lgamma", "tgamma", "gamma", "ceil", "floor", "nearbyint", "rint",
    "lrint", "llrint", "round", "lround", "llround", "roundeven", "trunc", "fromfp", "fromfpx",
    "ufromfp", "ufromfpx", "fmod", "remainder", "remquo", "drem", "copysign", "nan", "nextafter",
    "nexttoward", "nextup", "nextdown", "canonicalize", "fdim", "fmax", "fmin", "fmaxmag",
    "fminmag", "fmaximum", "fminimum", "fmaximum_mag", "fminimum_mag", "fmaximum_num",
    "fminimum_num", "fmaximum_mag_num", "fminimum_mag_num", "fma", "getpayload",
    "setpayload", "setpayloadsig", "totalorder", "totalordermag", "j0", "j1", "jn", "y0", "y1",
    "yn", "significand", "finite", "isinf", "isnan", "iszero", "issignaling", "iscanonical",
    "iseqsig", "sincos", "pow10"};

// The narrowing functions: <type><operation><suffix> (fadd, daddl, f32mulf64, ...).
constexpr std::string_view kNarrowingTypes[] = {"f", "d", "f32", "f64", "f128", "f32x", "f64x"};
constexpr std::string_view kNarrowingOps[] = {"add", "sub", "mul", "div", "fma", "sqrt"};

// The other names <cmath> declares at global scope with glibc (its <stdlib.h> and POSIX types;
// `echo '#include <cmath>' | g++ -std=gnu++20 -E -x c++ -` declares them).
constexpr std::string_view kCGlobals[] = {
    "main", "std", "abort", "abs", "labs", "llabs", "div", "ldiv", "lldiv", "div_t", "ldiv_t",
    "lldiv_t", "aligned_alloc", "alloca", "malloc", "calloc", "realloc", "reallocarray", "free",
    "valloc", "posix_memalign", "arc4random", "arc4random_buf", "arc4random_uniform", "atexit",
    "at_quick_exit", "on_exit", "exit", "quick_exit", "atof", "atoi", "atol", "atoll", "bsearch", "qsort", "qsort_r", "canonicalize_file_name",
    "clearenv", "getenv", "secure_getenv", "putenv", "setenv", "unsetenv", "drand48", "erand48",
    "lrand48", "nrand48", "mrand48", "jrand48", "srand48", "seed48", "lcong48", "drand48_r",
    "erand48_r", "lrand48_r", "nrand48_r", "mrand48_r", "jrand48_r", "srand48_r", "seed48_r",
    "lcong48_r", "drand48_data", "rand", "rand_r", "srand", "random", "srandom", "random_r",
    "srandom_r", "random_data", "initstate", "initstate_r", "setstate", "setstate_r", "ecvt",
    "fcvt", "gcvt", "ecvt_r", "fcvt_r", "qecvt", "qfcvt", "qgcvt", "qecvt_r", "qfcvt_r", "l64a",
    "a64l", "getloadavg", "getpt", "getsubopt", "grantpt", "unlockpt", "ptsname", "ptsname_r",
    "posix_openpt", "mblen", "mbtowc", "wctomb", "mbstowcs", "wcstombs", "mkdtemp", "mktemp",
    "mkstemp", "mkstemp64", "mkstemps", "mkstemps64", "mkostemp", "mkostemp64", "mkostemps",
    "mkostemps64", "realpath", "rpmatch", "system", "select", "pselect", "signgam",
    "comparison_fn_t", "double_t", "float_t", "size_t", "ssize_t", "wchar_t", "int8_t",
    "int16_t", "int32_t", "int64_t", "u_int8_t", "u_int16_t", "u_int32_t", "u_int64_t",
    "u_char", "u_short", "u_int", "u_long", "u_quad_t", "quad_t", "uint", "ulong", "ushort",
    "register_t", "blkcnt_t", "blkcnt64_t", "blksize_t", "caddr_t", "clock_t", "clockid_t",
    "daddr_t", "dev_t", "fd_mask", "fd_set", "fsblkcnt_t", "fsblkcnt64_t", "fsfilcnt_t",
    "fsfilcnt64_t", "fsid_t", "gid_t", "id_t", "ino_t", "ino64_t", "key_t", "locale_t", "loff_t",
    "mode_t", "nlink_t", "off_t", "off64_t", "pid_t", "sigset_t", "suseconds_t", "time_t",
    "timer_t", "timespec", "timeval", "uid_t", "useconds_t", "pthread_t", "pthread_attr_t",
    "pthread_barrier_t", "pthread_barrierattr_t", "pthread_cond_t", "pthread_condattr_t",
    "pthread_key_t", "pthread_mutex_t", "pthread_mutexattr_t", "pthread_once_t",
    "pthread_rwlock_t", "pthread_rwlockattr_t", "pthread_spinlock_t", "max_align_t",
    "ptrdiff_t"};

// Python's keywords and soft keywords (keyword.kwlist, keyword.softkwlist and 3.12's `type`),
// the functions' own arguments, and the module and builtins the generated code calls.
constexpr std::string_view kPythonWords[] = {
    "False", "None", "True", "and", "as", "assert", "async", "await", "break", "class",
    "continue", "def", "del", "elif", "else", "except", "finally", "for", "from", "global", "if",
    "import", "in", "is", "lambda", "nonlocal", "not", "or", "pass", "raise", "return", "try",
    "while", "with", "yield", "match", "case", "type", "q", "q_dot", "q_ddot", "tau", "t",
    "math", "float", "len", "range", "ValueError"};

template <std::size_t N>
bool contains(const std::string_view (&words)[N], std::string_view name) {
  return std::find(std::begin(words), std::end(words), name) != std::end(words);
}

// `name` is a function of <math.h> with one of its type suffixes (and an optional "_r"), or
// one of the string conversions of <stdlib.h> (strtod, strfromf128, strtof64_l, ...).
bool math_function(std::string_view name) {
  if (name.starts_with("strto") || name.starts_with("strfrom")) {
    if (name.ends_with("_l")) name.remove_suffix(2);
    name.remove_prefix(name.starts_with("strto") ? 5 : 7);
    // strtod, strtold, strtol, strtoll, strtoul, strtoull, strtoq, strtouq; strtof, strtof128, ...
    for (std::string_view integer : {"d", "ld", "l", "ll", "ul", "ull", "q", "uq"}) {
      if (name == integer) return true;
    }
    return !name.empty() && contains(kFloatSuffixes, name);
  }
  if (name.ends_with("_r")) name.remove_suffix(2);
  for (std::string_view suffix : kFloatSuffixes) {
    if (name.size() <= suffix.size() || !name.ends_with(suffix)) continue;
    const std::string_view base = name.substr(0, name.size() - suffix.size());
    if (contains(kMathFunctions, base)) return true;
    for (std::string_view type : kNarrowingTypes) {
      if (base.starts_with(type) && contains(kNarrowingOps, base.substr(type.size()))) return true;
    }
  }
  return false;
}

bool math_constant(std::string_view name) {
  if (!name.starts_with("M_")) return false;
  name.remove_prefix(2);
  for (std::string_view suffix : kFloatSuffixes) {
    if (name.size() > suffix.size() && name.ends_with(suffix) &&
        contains(kMathConstants, name.substr(0, name.size() - suffix.size()))) {
      return true;
    }
  }
  return false;
}

// Where an exported identifier lives: what it may not be called there.
enum class Scope {
  kMember,     // a C++ Parameters member or a Python keyword argument
  kNamespace,  // the C++ namespace, at global scope beside <cmath>'s declarations and main()
};

bool reserved(std::string_view name, Language language, Scope scope) {
  // no reserved name ends with '_' (none of the lists' words, none the patterns match), so
  // step 3 of the rule ends: one '_' makes a name unreserved, more make it unused
  if (name.ends_with("_")) return false;
  if (language == Language::kPython) return contains(kPythonWords, name);
  if (contains(kCppKeywords, name) || contains(kCppMacros, name) || math_constant(name)) {
    return true;
  }
  if (scope == Scope::kMember) return name == "Parameters";  // a member may not name its class
  return contains(kCGlobals, name) || math_function(name);
}

// The identifiers of `names` under the rule above, in order; distinct when the names are.
std::vector<std::string> export_identifiers(const std::vector<std::string>& names,
                                            Language language, Scope scope) {
  std::set<std::string> used(names.begin(), names.end());
  std::vector<std::string> out;
  for (const std::string& name : names) {
    std::string id;
    for (char c : name) id += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    if (id.empty() || std::isdigit(static_cast<unsigned char>(id[0]))) id = "model_" + id;
    if (id.starts_with("_")) id = "p" + id;
    if (id == name && !reserved(id, language, scope)) {
      out.push_back(id);
      continue;
    }
    while (reserved(id, language, scope) || used.count(id) > 0) id += "_";
    used.insert(id);
    out.push_back(id);
  }
  return out;
}

// The renamed identifiers as "old → new" lines for the file's header comment.
std::vector<std::string> renamed(const std::vector<std::string>& names,
                                 const std::vector<std::string>& ids) {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (names[k] != ids[k]) out.push_back(fmt::format("{} → {}", names[k], ids[k]));
  }
  return out;
}

// ----------------------------------------------------------------------------------------
// printing a tape

struct Syntax {
  bool python = false;
  std::vector<std::string> inputs;  // the text of each input slot
  std::string pow_int = "detail::pow_int";  // C++: the file's binary powering
};

std::string literal(double v, bool python) {
  if (std::isinf(v)) {
    const char* inf = python ? "math.inf" : "HUGE_VAL";
    return v > 0 ? inf : fmt::format("(-{})", inf);
  }
  std::string s = fmt::format("{}", v);  // shortest round-trip decimal
  if (s.find_first_of(".en") == std::string::npos) s += ".0";
  return v < 0 ? "(" + s + ")" : s;
}

class TapePrinter {
 public:
  TapePrinter(const Tape& tape, const Syntax& syntax) : tape_(tape), syntax_(syntax) {}

  // One line per instruction, `indent` before each, in print_order().
  [[nodiscard]] std::string body(std::string_view indent) const {
    std::string out;
    const auto& code = tape_.instructions();
    for (std::size_t k : print_order()) {
      out += fmt::format("{}{}{} = {}{}\n", indent, syntax_.python ? "" : "const double ",
                         local(k), expression(code[k]), syntax_.python ? "" : ";");
    }
    return out;
  }
  // The instructions depth first from each output in turn, each right after its operands.
  // The tape's own order (by level) suits its interpreter, which runs a level's operations as
  // one loop, but keeps every value of a level alive at once; compiled, that spills most of
  // them to the stack and makes a function larger than the instruction cache (36 KB for a
  // 7-joint arm's forward dynamics). Depth first, a value dies soon after it is made. The
  // operations and their operands are the same, so are the numbers.
  [[nodiscard]] std::vector<std::size_t> print_order() const {
    const auto& code = tape_.instructions();
    const std::size_t base = tape_.num_inputs() + tape_.constants().size();
    std::vector<char> done(code.size(), 0);
    std::vector<std::size_t> order;
    order.reserve(code.size());
    // (instruction, operands visited so far)
    std::vector<std::pair<std::size_t, int>> stack;
    auto pending = [&](std::int32_t slot) {
      const auto s = static_cast<std::size_t>(slot);
      return s >= base && !done[s - base];
    };
    // First the library calls on the inputs (sin q_i, cos q_i): a call clobbers every
    // floating-point register, so a value alive across one is spilled; up front, none is.
    for (std::size_t k = 0; k < code.size(); ++k) {
      const Instruction& in = code[k];
      const auto input = [&](std::int32_t slot) { return static_cast<std::size_t>(slot) < base; };
      if (library_call(in.op) && input(in.a) && (!binary(in.op) || input(in.b))) {
        done[k] = 1;
        order.push_back(k);
      }
    }
    for (std::int32_t root : tape_.outputs()) {
      if (!pending(root)) continue;
      stack.emplace_back(static_cast<std::size_t>(root) - base, 0);
      while (!stack.empty()) {
        const auto [k, visited] = stack.back();
        const Instruction& in = code[k];
        if (visited == 2 || done[k]) {
          if (!done[k]) {
            done[k] = 1;
            order.push_back(k);
          }
          stack.pop_back();
          continue;
        }
        stack.back().second = visited + 1;
        const std::int32_t operand = visited == 0 ? in.a : in.b;
        if ((visited == 0 || binary(in.op)) && pending(operand)) {
          stack.emplace_back(static_cast<std::size_t>(operand) - base, 0);
        }
      }
    }
    for (std::size_t k = 0; k < code.size(); ++k) {
      if (!done[k]) order.push_back(k);  // read by no output (none are built so)
    }
    return order;
  }
  static bool binary(Op op) {
    return op == Op::kAdd || op == Op::kSub || op == Op::kMul || op == Op::kDiv || op == Op::kPow;
  }
  // an operation printed as a call of <cmath> (kInvSqrt too: 1.0 / std::sqrt)
  static bool library_call(Op op) {
    switch (op) {
      case Op::kAdd: case Op::kSub: case Op::kMul: case Op::kDiv: case Op::kNeg: case Op::kInv:
      case Op::kSquare: case Op::kPowInt:
        return false;
      default:
        return true;
    }
  }
  // The instructions split in two, each part one line per instruction: those that read no
  // input slot of `deferred` (directly or through another instruction), then those that do;
  // so code between the parts may compute the deferred inputs from the first part's outputs.
  [[nodiscard]] std::pair<std::string, std::string> split_body(
      std::string_view indent, const std::vector<bool>& deferred) const {
    const auto& code = tape_.instructions();
    const std::size_t base = tape_.num_inputs() + tape_.constants().size();
    std::vector<bool> late(code.size(), false);
    auto reads_late = [&](std::int32_t slot) {
      const auto s = static_cast<std::size_t>(slot);
      if (s < tape_.num_inputs()) return static_cast<bool>(deferred[s]);
      return s >= base && late[s - base];
    };
    std::pair<std::string, std::string> out;
    for (std::size_t k = 0; k < code.size(); ++k) {
      const Instruction& in = code[k];
      late[k] = reads_late(in.a) || (binary(in.op) && reads_late(in.b));
    }
    // print_order() puts operands first, so each part keeps it
    for (std::size_t k : print_order()) {
      (late[k] ? out.second : out.first) +=
          fmt::format("{}const double {} = {};\n", indent, local(k), expression(code[k]));
    }
    return out;
  }
  // The text of output k.
  [[nodiscard]] std::string output(std::size_t k) const {
    return operand(tape_.outputs()[k]);
  }

 private:
  [[nodiscard]] std::string local(std::size_t k) const {
    return fmt::format("{}v{}", syntax_.python ? "_" : "", k);
  }
  [[nodiscard]] std::string operand(std::int32_t slot) const {
    const auto s = static_cast<std::size_t>(slot);
    const std::size_t ni = tape_.num_inputs(), nc = tape_.constants().size();
    if (s < ni) return syntax_.inputs[s];
    if (s < ni + nc) return literal(tape_.constants()[s - ni], syntax_.python);
    return local(s - ni - nc);
  }
  [[nodiscard]] std::string call(std::string_view cpp, std::string_view py, std::int32_t a) const {
    return fmt::format("{}({})", syntax_.python ? py : cpp, operand(a));
  }
  [[nodiscard]] std::string expression(const Instruction& in) const {
    const std::string a = operand(in.a);
    auto b = [&] { return operand(in.b); };
    switch (in.op) {
      case Op::kAdd: return a + " + " + b();
      case Op::kSub: return a + " - " + b();
      case Op::kMul: return a + " * " + b();
      case Op::kDiv: return a + " / " + b();
      case Op::kNeg: return "-" + a;
      case Op::kInv: return "1.0 / " + a;
      case Op::kSquare: return a + " * " + a;
      case Op::kPow: return fmt::format("{}({}, {})", syntax_.python ? "math.pow" : "std::pow", a, b());
      case Op::kPowInt: return fmt::format("{}({}, {})", syntax_.python ? "_pow_int" : syntax_.pow_int, a, in.b);
      case Op::kSqrt: return call("std::sqrt", "math.sqrt", in.a);
      case Op::kInvSqrt: return "1.0 / " + call("std::sqrt", "math.sqrt", in.a);
      case Op::kSin: return call("std::sin", "math.sin", in.a);
      case Op::kCos: return call("std::cos", "math.cos", in.a);
      case Op::kTan: return call("std::tan", "math.tan", in.a);
      case Op::kAsin: return call("std::asin", "math.asin", in.a);
      case Op::kAcos: return call("std::acos", "math.acos", in.a);
      case Op::kAtan: return call("std::atan", "math.atan", in.a);
      case Op::kExp: return call("std::exp", "math.exp", in.a);
      case Op::kLog: return call("std::log", "math.log", in.a);
      case Op::kAbs: return call("std::abs", "math.fabs", in.a);
      case Op::kSinh: return call("std::sinh", "math.sinh", in.a);
      case Op::kCosh: return call("std::cosh", "math.cosh", in.a);
      case Op::kTanh: return call("std::tanh", "math.tanh", in.a);
    }
    return "0.0";
  }

  const Tape& tape_;
  const Syntax syntax_;  // a copy: callers pass temporaries
};

// ----------------------------------------------------------------------------------------
// the exported functions

// M's upper triangle, row by row.
std::vector<GiNaC::ex> upper_triangle(const std::vector<GiNaC::ex>& M, std::size_t n) {
  std::vector<GiNaC::ex> out;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) out.push_back(M[i * n + j]);
  return out;
}

// "  name[i*n + j] = <output>;" for an upper triangle from output k on (k moves past it), each
// off-diagonal entry written to its mirror too.
std::string symmetric_assignments(const TapePrinter& printer, std::size_t& k,
                                  std::string_view name, std::size_t n) {
  std::string out;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i; j < n; ++j) {
      const std::string v = printer.output(k++);
      out += fmt::format("  {}[{}] = {};\n", name, i * n + j, v);
      if (j != i) out += fmt::format("  {}[{}] = {};\n", name, j * n + i, v);
    }
  }
  return out;
}

// Which outputs a function computes.
struct Parts {
  bool M = false, f = false, G = false, gamma = false;
};

struct FunctionSpec {
  const char* name;
  Parts parts;
  bool velocity;  // takes q̇
  const char* doc;
};

constexpr FunctionSpec kFunctions[] = {
    {"mass_matrix", {true, false, false, false}, false,
     "M(q, t) = ∂²L/∂q̇∂q̇, n × n"},
    {"forces", {false, true, false, false}, true,
     "f(q, q̇, t) = ∂L/∂q − (∂²L/∂q̇∂q) q̇ − ∂²L/∂q̇∂t + Q (generalized forces included)"},
    {"mass_matrix_and_forces", {true, true, false, false}, true,
     "M and f together (their common subexpressions computed once)"},
    {"constraint_jacobian", {false, false, true, false}, false,
     "G(q, t) = ∂g/∂q, m × n"},
    {"constraint_gamma", {false, false, false, true}, true,
     "γ(q, q̇, t) = −(∂(G q̇ + ∂g/∂t)/∂q q̇ + ∂(G q̇ + ∂g/∂t)/∂t), so that G q̈ = γ"},
};

Tape function_tape(const System::Impl& s, const Parts& parts) {
  std::vector<GiNaC::symbol> inputs;
  inputs.insert(inputs.end(), s.q.begin(), s.q.end());
  inputs.insert(inputs.end(), s.qd.begin(), s.qd.end());
  inputs.push_back(s.t);
  inputs.insert(inputs.end(), s.params.begin(), s.params.end());
  detail::TapeBuilder b(inputs, inputs.size() - s.params.size());  // as System's
  detail::define_intermediates(b, s);
  const auto n = static_cast<std::size_t>(s.n);
  // the order of System's dynamics tape: M's upper triangle, f, G, γ
  if (parts.M) {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j) b.add_output(s.M[i * n + j]);
  }
  if (parts.f) {
    for (const auto& e : s.f) b.add_output(e);
  }
  if (parts.G) {
    for (const auto& e : s.G) b.add_output(e);
  }
  if (parts.gamma) {
    for (const auto& e : s.gamma) b.add_output(e);
  }
  return b.build();
}

// The file's first comment. `renames` ("old → new") are the user's names written under
// another identifier, listed after `rule` (the sentence that says why), wrapped at 100 columns.
std::string header_comment(const System::Impl& s, const ExportOptions& options,
                           std::string_view mark, const std::vector<std::string>& renames,
                           std::string_view rule) {
  std::string out;
  auto line = [&](const std::string& text) {
    out += fmt::format("{}{}{}\n", mark, text.empty() ? "" : " ", text);
  };
  // the source on one comment line: control characters (a newline in a path) become '?'
  std::string source = options.source;
  for (char& c : source) c = static_cast<unsigned char>(c) < 0x20 || c == 0x7f ? '?' : c;
  line(fmt::format("Equations of motion{}, generated by rigid; do not edit.",
                   source.empty() ? "" : fmt::format(" of {}", source)));
  line("");
  line(s.balls.empty() ? "  M(q, t) q̈ = f(q, q̇, t) + Gᵀ λ,   G(q, t) q̈ = γ(q, q̇, t)"
                       : "  M(q) v̇ = f(q, v),   dq/dt = v and, for a ball's quaternion, ½ q ⊗ (0, ω)");
  line("");
  std::string coords;
  for (std::size_t i = 0; i < s.coord_names.size(); ++i) {
    coords += fmt::format("{}q[{}] = {}", i ? ", " : "", i, s.coord_names[i]);
  }
  if (s.balls.empty()) {
    line(fmt::format("Coordinates (n = {}): {}.", s.n, coords));
  } else {
    std::string velocities;
    for (std::size_t i = 0; i < s.velocity_names.size(); ++i) {
      velocities += fmt::format("{}q_dot[{}] = {}", i ? ", " : "", i, s.velocity_names[i]);
    }
    line(fmt::format("Coordinates (nq = {}): {}.", s.nq, coords));
    line(fmt::format("Velocities (nv = {}; a ball's ω in its body's frame): {}.", s.n, velocities));
  }
  if (s.m > 0) {
    std::string cons;
    for (std::size_t k = 0; k < s.constraint_names.size(); ++k) {
      cons += fmt::format("{}{}", k ? ", " : "", s.constraint_names[k]);
    }
    line(fmt::format("Constraints (m = {}), rows of G and γ: {}.", s.m, cons));
  } else {
    line("Constraints: none (m = 0; G and γ are empty).");
  }
  line("Units: SI (the model's parameters and coordinates as given).");
  if (!renames.empty()) {
    // columns as displayed: UTF-8 continuation bytes ("→" is three bytes) take none
    auto columns = [](const std::string& text) {
      return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
        return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
      }));
    };
    line("");
    // the words of the rule, then the names, wrapped at 100 columns
    std::vector<std::string> words;
    std::string word;
    for (char c : fmt::format("Renamed ({}):", rule)) {
      if (c != ' ') {
        word += c;
      } else if (!word.empty()) {
        words.push_back(std::exchange(word, ""));
      }
    }
    words.push_back(word);
    for (std::size_t k = 0; k < renames.size(); ++k) {
      words.push_back(renames[k] + (k + 1 < renames.size() ? "," : "."));
    }
    std::string text;
    for (const std::string& w : words) {
      if (!text.empty() && mark.size() + 1 + columns(text) + 1 + columns(w) > 100) {
        line(text);
        text = " ";
      }
      text += text.empty() || text == " " ? w : " " + w;
    }
    line(text);
  }
  return out;
}

// ----------------------------------------------------------------------------------------
// C++

// The file's binary powering: x^k (k ≥ 1) as the engine's tape computes it.
constexpr const char* kCppPowInt =
    "/// x^k (k ≥ 1) by binary powering, as the engine computes it.\n"
    "inline double pow_int(double x, int k) {\n"
    "  double v = 1.0;\n"
    "  while (k > 0) {\n"
    "    if (k & 1) v *= x;\n"
    "    x *= x;\n"
    "    k >>= 1;\n"
    "  }\n"
    "  return v;\n"
    "}\n";

// `struct Parameters { double <name> = <value>; ... };` with the model's names beside renamed
// members.
std::string cpp_parameters(const System::Impl& s, const std::vector<std::string>& params) {
  std::string out = "struct Parameters {\n";
  for (std::size_t k = 0; k < params.size(); ++k) {
    out += fmt::format("  double {} = {};{}\n", params[k], literal(s.param_values[k], false),
                       params[k] != s.param_names[k] ? fmt::format("  // {}", s.param_names[k]) : "");
  }
  return out + "};\n";
}

std::string cpp_function(const System::Impl& s, const FunctionSpec& fn,
                         const std::vector<std::string>& params) {
  const auto n = static_cast<std::size_t>(s.n);
  const auto m = static_cast<std::size_t>(s.m);
  Syntax syntax;
  for (std::size_t i = 0; i < n; ++i) syntax.inputs.push_back(fmt::format("q[{}]", i));
  for (std::size_t i = 0; i < n; ++i) syntax.inputs.push_back(fmt::format("q_dot[{}]", i));
  syntax.inputs.push_back("t");
  for (const std::string& p : params) syntax.inputs.push_back("p." + p);
  const Tape tape = function_tape(s, fn.parts);
  const TapePrinter printer(tape, syntax);

  auto array = [](std::string_view type, std::string_view name, std::size_t size) {
    return size > 0 ? fmt::format("{} {}[{}]", type, name, size)
                    : fmt::format("[[maybe_unused]] {}* {}", type, name);
  };
  std::vector<std::string> args = {array("const double", "q", n)};
  if (fn.velocity) args.push_back(array("const double", "q_dot", n));
  args.emplace_back("[[maybe_unused]] double t");
  if (fn.parts.M) args.push_back(array("double", "M", n * n));
  if (fn.parts.f) args.push_back(array("double", "f", n));
  if (fn.parts.G) args.push_back(array("double", "G", m * n));
  if (fn.parts.gamma) args.push_back(array("double", "gamma", m));
  args.emplace_back("[[maybe_unused]] const Parameters& p = {}");
  // q is unused by a function of constants only, q_dot by one that q̇ does not enter
  args[0] = "[[maybe_unused]] " + args[0];
  if (fn.velocity) args[1] = "[[maybe_unused]] " + args[1];

  std::string out = fmt::format("/// {}\ninline void {}({}) {{\n", fn.doc, fn.name,
                                fmt::join(args, ", "));
  out += printer.body("  ");
  std::size_t k = 0;
  if (fn.parts.M) out += symmetric_assignments(printer, k, "M", n);
  if (fn.parts.f) {
    for (std::size_t i = 0; i < n; ++i) out += fmt::format("  f[{}] = {};\n", i, printer.output(k++));
  }
  if (fn.parts.G) {
    for (std::size_t i = 0; i < m * n; ++i) out += fmt::format("  G[{}] = {};\n", i, printer.output(k++));
  }
  if (fn.parts.gamma) {
    for (std::size_t i = 0; i < m; ++i) out += fmt::format("  gamma[{}] = {};\n", i, printer.output(k++));
  }
  return out + "}\n";
}

// The inverse and forward dynamics of a system without constraints, on the M and f of
// mass_matrix_and_forces (plain loops: the file stays dependency-free). A system with
// constraints gets a comment saying why they are missing: its multipliers enter the equations.
std::string cpp_dynamics(const System::Impl& s) {
  if (s.m > 0) {
    return fmt::format(
        "// inverse_dynamics and forward_dynamics are not exported: the system has constraints (m = "
        "{}),\n// whose multipliers λ enter M q̈ = f + τ + Gᵀλ (with G q̈ = γ) and are not in "
        "M and f alone.\n",
        s.m);
  }
  const auto n = static_cast<std::size_t>(s.n);
  auto array = [](std::string_view type, std::string_view name, std::size_t size) {
    return fmt::format("{} {}[{}]", type, name, size);
  };
  std::string out = fmt::format(
      "/// τ = M q̈ − f (inverse dynamics): the generalized force that, added to the model's own "
      "forces,\n/// gives the motion the acceleration q̈.\n"
      "inline void inverse_dynamics({}, {}, {}, double t, {}, const Parameters& p = {{}}) {{\n",
      array("const double", "q", n), array("const double", "q_dot", n),
      array("const double", "q_ddot", n), array("double", "tau", n));
  out += "  constexpr int n = kNumCoordinates;\n"
         "  double M[n * n];\n"
         "  double f[n];\n"
         "  mass_matrix_and_forces(q, q_dot, t, M, f, p);\n"
         "  for (int i = 0; i < n; ++i) {\n"
         "    double s = 0.0;\n"
         "    for (int j = 0; j < n; ++j) s += M[i * n + j] * q_ddot[j];\n"
         "    tau[i] = s - f[i];\n"
         "  }\n"
         "}\n\n";
  out += fmt::format(
      "/// q̈ = M⁻¹ (f + τ) (forward dynamics), M factored in place as L Lᵀ (Cholesky). Returns "
      "false,\n/// q_ddot unchanged, where a pivot is not positive (or NaN): M is not positive "
      "definite there,\n/// which a valid model's never is.\n"
      "[[nodiscard]] inline bool forward_dynamics({}, {}, {}, double t, {}, const Parameters& p = "
      "{{}}) {{\n",
      array("const double", "q", n), array("const double", "q_dot", n),
      array("const double", "tau", n), array("double", "q_ddot", n));
  out += "  constexpr int n = kNumCoordinates;\n"
         "  double L[n * n];\n"
         "  double b[n];\n"
         "  mass_matrix_and_forces(q, q_dot, t, L, b, p);\n"
         "  for (int i = 0; i < n; ++i) b[i] += tau[i];\n"
         "  // L Lᵀ = M, column by column: L's lower triangle overwrites M's\n"
         "  for (int j = 0; j < n; ++j) {\n"
         "    double d = L[j * n + j];\n"
         "    for (int k = 0; k < j; ++k) d -= L[j * n + k] * L[j * n + k];\n"
         "    if (!(d > 0.0)) return false;\n"
         "    const double l = std::sqrt(d);\n"
         "    L[j * n + j] = l;\n"
         "    for (int i = j + 1; i < n; ++i) {\n"
         "      double s = L[i * n + j];\n"
         "      for (int k = 0; k < j; ++k) s -= L[i * n + k] * L[j * n + k];\n"
         "      L[i * n + j] = s / l;\n"
         "    }\n"
         "  }\n"
         "  // L y = b, then Lᵀ x = y (y and x overwrite b)\n"
         "  for (int i = 0; i < n; ++i) {\n"
         "    for (int k = 0; k < i; ++k) b[i] -= L[i * n + k] * b[k];\n"
         "    b[i] /= L[i * n + i];\n"
         "  }\n"
         "  for (int i = n - 1; i >= 0; --i) {\n"
         "    for (int k = i + 1; k < n; ++k) b[i] -= L[k * n + i] * b[k];\n"
         "    b[i] /= L[i * n + i];\n"
         "  }\n"
         "  for (int i = 0; i < n; ++i) q_ddot[i] = b[i];\n"
         "  return true;\n"
         "}\n";
  return out;
}

// ----------------------------------------------------------------------------------------
// Python

std::string python_function(const System::Impl& s, const FunctionSpec& fn,
                            const std::vector<std::string>& params) {
  const auto n = static_cast<std::size_t>(s.n);
  const auto m = static_cast<std::size_t>(s.m);
  Syntax syntax;
  syntax.python = true;
  for (std::size_t i = 0; i < n; ++i) syntax.inputs.push_back(fmt::format("_q[{}]", i));
  for (std::size_t i = 0; i < n; ++i) syntax.inputs.push_back(fmt::format("_qd[{}]", i));
  syntax.inputs.push_back("t");
  for (const std::string& p : params) syntax.inputs.push_back(p);
  const Tape tape = function_tape(s, fn.parts);
  const TapePrinter printer(tape, syntax);

  std::string signature = fn.velocity ? "q, q_dot, t=0.0" : "q, t=0.0";
  if (!params.empty()) {
    signature += ", *";
    for (std::size_t k = 0; k < params.size(); ++k) {
      signature += fmt::format(", {}={}", params[k], literal(s.param_values[k], true));
    }
  }
  std::string out = fmt::format("def {}({}):\n    \"\"\"{}.\"\"\"\n", fn.name, signature, fn.doc);
  out += fmt::format("    _q = _vector(q, {}, \"q\")\n", n);
  if (fn.velocity) out += fmt::format("    _qd = _vector(q_dot, {}, \"q_dot\")\n", n);
  out += "    t = float(t)\n";
  out += printer.body("    ");
  std::size_t k = 0;
  std::vector<std::string> results;
  if (fn.parts.M) {
    std::vector<std::string> M(n * n);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j) M[i * n + j] = M[j * n + i] = printer.output(k++);
    std::vector<std::string> rows;
    for (std::size_t i = 0; i < n; ++i) {
      rows.push_back(fmt::format("[{}]", fmt::join(M.begin() + static_cast<std::ptrdiff_t>(i * n),
                                                   M.begin() + static_cast<std::ptrdiff_t>((i + 1) * n), ", ")));
    }
    results.push_back(fmt::format("[{}]", fmt::join(rows, ", ")));
  }
  if (fn.parts.f) {
    std::vector<std::string> f;
    for (std::size_t i = 0; i < n; ++i) f.push_back(printer.output(k++));
    results.push_back(fmt::format("[{}]", fmt::join(f, ", ")));
  }
  if (fn.parts.G) {
    std::vector<std::string> rows;
    for (std::size_t a = 0; a < m; ++a) {
      std::vector<std::string> row;
      for (std::size_t i = 0; i < n; ++i) row.push_back(printer.output(k++));
      rows.push_back(fmt::format("[{}]", fmt::join(row, ", ")));
    }
    results.push_back(fmt::format("[{}]", fmt::join(rows, ", ")));
  }
  if (fn.parts.gamma) {
    std::vector<std::string> g;
    for (std::size_t a = 0; a < m; ++a) g.push_back(printer.output(k++));
    results.push_back(fmt::format("[{}]", fmt::join(g, ", ")));
  }
  out += fmt::format("    return {}\n", fmt::join(results, ", "));
  return out;
}

// The Python counterpart of cpp_dynamics: the same operations in the same order, so the same
// numbers.
std::string python_dynamics(const System::Impl& s, const std::vector<std::string>& params) {
  if (s.m > 0) {
    return fmt::format(
        "# inverse_dynamics and forward_dynamics are not exported: the system has constraints (m = "
        "{}),\n# whose multipliers λ enter M q̈ = f + τ + Gᵀλ (with G q̈ = γ) and are not in "
        "M and f alone.\n",
        s.m);
  }
  std::string signature, call;
  for (std::size_t k = 0; k < params.size(); ++k) {
    signature += fmt::format(", {}={}", params[k], literal(s.param_values[k], true));
    call += fmt::format(", {0}={0}", params[k]);
  }
  if (!params.empty()) signature = ", *" + signature;
  std::string out =
      "# M and f under a name that no keyword argument (a parameter) can hide\n"
      "_mass_matrix_and_forces = mass_matrix_and_forces\n\n\n"
      "def _inverse_dynamics(M, f, q_ddot):\n"
      "    tau = []\n"
      "    for i in range(len(f)):\n"
      "        s = 0.0\n"
      "        for j in range(len(f)):\n"
      "            s += M[i][j] * q_ddot[j]\n"
      "        tau.append(s - f[i])\n"
      "    return tau\n\n\n"
      "def _forward_dynamics(M, f, tau):\n"
      "    n = len(f)\n"
      "    b = [f[i] + tau[i] for i in range(n)]\n"
      "    L = M  # L Lᵀ = M, column by column: L's lower triangle overwrites M's\n"
      "    for j in range(n):\n"
      "        d = L[j][j]\n"
      "        for k in range(j):\n"
      "            d -= L[j][k] * L[j][k]\n"
      "        if not d > 0.0:\n"
      "            raise ValueError(f\"forward_dynamics: the mass matrix is not positive definite "
      "at this q: pivot {j} ({COORDINATES[j]}) of its Cholesky factorization is {d!r}, expected > "
      "0; check the model's masses, inertias and parameters\")\n"
      "        l = math.sqrt(d)\n"
      "        L[j][j] = l\n"
      "        for i in range(j + 1, n):\n"
      "            s = L[i][j]\n"
      "            for k in range(j):\n"
      "                s -= L[i][k] * L[j][k]\n"
      "            L[i][j] = s / l\n"
      "    # L y = b, then Lᵀ x = y (y and x overwrite b)\n"
      "    for i in range(n):\n"
      "        for k in range(i):\n"
      "            b[i] -= L[i][k] * b[k]\n"
      "        b[i] /= L[i][i]\n"
      "    for i in range(n - 1, -1, -1):\n"
      "        for k in range(i + 1, n):\n"
      "            b[i] -= L[k][i] * b[k]\n"
      "        b[i] /= L[i][i]\n"
      "    return b\n\n\n";
  out += fmt::format(
      "def inverse_dynamics(q, q_dot, q_ddot, t=0.0{}):\n"
      "    \"\"\"τ = M q̈ − f (inverse dynamics): the generalized force that, added to the model's "
      "own forces, gives the motion the acceleration q̈.\"\"\"\n"
      "    _qdd = _vector(q_ddot, {}, \"q_ddot\")\n"
      "    _M, _f = _mass_matrix_and_forces(q, q_dot, t{})\n"
      "    return _inverse_dynamics(_M, _f, _qdd)\n\n\n",
      signature, s.n, call);
  out += fmt::format(
      "def forward_dynamics(q, q_dot, tau, t=0.0{}):\n"
      "    \"\"\"q̈ = M⁻¹ (f + τ) (forward dynamics) by a Cholesky factorization M = L Lᵀ; raises "
      "ValueError where M is not positive definite (a pivot ≤ 0 or NaN), which a valid model's "
      "never is.\"\"\"\n"
      "    _tau = _vector(tau, {}, \"tau\")\n"
      "    _M, _f = _mass_matrix_and_forces(q, q_dot, t{})\n"
      "    return _forward_dynamics(_M, _f, _tau)\n",
      signature, s.n, call);
  return out;
}

std::string quoted(const std::string& s) { return "\"" + s + "\""; }

// ----------------------------------------------------------------------------------------
// C++, flat layout (ExportOptions::flat)

// The tree of the coordinates as M's pattern shows it: λ(j) = the last i < j with M_ij not
// identically zero (−1: none), kept where every such M_ij lies on the chain λ(j), λ(λ(j)), …
// (a tree's M: i is a joint on the path to j); otherwise the chain λ(j) = j − 1 (dense M).
// Factoring M = Lᵀ D L along λ then fills nothing outside the pairs of a coordinate and its
// ancestors [Featherstone2008, §6.5 "LTDL"]. Where an entry on the path is zero by the geometry
// (a free joint's three perpendicular slides: M_xy = m e_x · e_y) the pattern hides the tree;
// a tree derived by the recursions then gives it from its bodies (tree_columns).
std::vector<int> coordinate_tree(const System::Impl& s);

// The tree of the velocities from the bodies of a recursive derivation: a column's parent is
// the column before it on its body (a ball's three in order), or the last column of the
// nearest body above; empty when a parent would not come first.
std::vector<int> tree_columns(const System::Impl& s) {
  std::vector<int> lambda(static_cast<std::size_t>(s.n), -1);
  std::vector<int> last(s.tree_bodies.size(), -1);  // per body: its last column (or its parent's)
  for (std::size_t b = 0; b < s.tree_bodies.size(); ++b) {
    const detail::TreeBody& body = s.tree_bodies[b];
    int prev = body.parent >= 0 ? last[static_cast<std::size_t>(body.parent)] : -1;
    for (const detail::TreeJoint& J : body.joints) {
      for (std::size_t k = 0; k < (J.ball ? 3U : 1U); ++k) {
        const std::size_t c = J.coordinate + k;
        if (prev >= static_cast<int>(c)) return {};
        lambda[c] = prev;
        prev = static_cast<int>(c);
      }
    }
    last[b] = prev;
  }
  return lambda;
}

std::vector<int> coordinate_tree(const System::Impl& s) {
  const auto n = static_cast<std::size_t>(s.n);
  std::vector<int> lambda(n, -1);
  auto nonzero = [&](std::size_t i, std::size_t j) { return !s.M[i * n + j].is_zero(); };
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t i = 0; i < j; ++i) {
      if (nonzero(i, j)) lambda[j] = static_cast<int>(i);
    }
  }
  // every entry of M that is not identically zero pairs a coordinate with one on its chain
  auto holds = [&](const std::vector<int>& tree) {
    for (std::size_t j = 0; j < n; ++j) {
      std::vector<bool> on_chain(n, false);
      for (int i = tree[j]; i >= 0; i = tree[static_cast<std::size_t>(i)]) on_chain[static_cast<std::size_t>(i)] = true;
      for (std::size_t i = 0; i < j; ++i) {
        if (nonzero(i, j) && !on_chain[i]) return false;
      }
    }
    return true;
  };
  if (holds(lambda)) return lambda;
  if (std::vector<int> tree = tree_columns(s); !tree.empty() && holds(tree)) return tree;
  for (std::size_t k = 0; k < n; ++k) lambda[k] = static_cast<int>(k) - 1;
  return lambda;
}

// The ancestors of k along λ, nearest first.
std::vector<std::size_t> ancestors(const std::vector<int>& lambda, std::size_t k) {
  std::vector<std::size_t> out;
  for (int i = lambda[k]; i >= 0; i = lambda[static_cast<std::size_t>(i)]) {
    out.push_back(static_cast<std::size_t>(i));
  }
  return out;
}

// The file's factor() and solve(), unrolled along λ: H holds M on the pairs (k, i), i = k or an
// ancestor of k, at H[k*n + i]; factor() overwrites it with D (diagonal) and L (unit lower
// triangular, M = Lᵀ D L); solve() overwrites x with M⁻¹ x.
std::string flat_factor_and_solve(const std::vector<int>& lambda) {
  const std::size_t n = lambda.size();
  std::string out =
      "/// M = Lᵀ D L in place along the tree of the coordinates (Featherstone, \"Rigid Body "
      "Dynamics\n/// Algorithms\", 2008, §6.5): H[k*n + i] holds M_ki for i = k and each "
      "ancestor i of k, and\n/// receives D_kk and L_ki. Returns false where a pivot D_kk is not "
      "positive (or is NaN).\n"
      "[[nodiscard]] inline bool factor(double* H) {\n";
  std::string pivots;
  for (std::size_t k = n; k-- > 0;) {
    for (std::size_t i : ancestors(lambda, k)) {
      out += fmt::format("  {{\n    const double a = H[{}] / H[{}];\n", k * n + i, k * n + k);
      out += fmt::format("    H[{}] -= a * H[{}];\n", i * n + i, k * n + i);
      for (std::size_t j : ancestors(lambda, i)) {
        out += fmt::format("    H[{}] -= a * H[{}];\n", i * n + j, k * n + j);
      }
      out += fmt::format("    H[{}] = a;\n  }}\n", k * n + i);
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    pivots += fmt::format("{}(H[{}] > 0.0)", k ? " & " : "", k * n + k);
  }
  out += fmt::format("  return {};\n}}\n\n", pivots);
  out += "/// x ← M⁻¹ x, with H from factor(): Lᵀ y = x, z = D⁻¹ y, L x = z.\n"
         "inline void solve(const double* H, double* x) {\n";
  for (std::size_t i = n; i-- > 0;) {
    for (std::size_t j : ancestors(lambda, i)) {
      out += fmt::format("  x[{}] -= H[{}] * x[{}];\n", j, i * n + j, i);
    }
  }
  for (std::size_t i = 0; i < n; ++i) out += fmt::format("  x[{}] /= H[{}];\n", i, i * n + i);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j : ancestors(lambda, i)) {
      out += fmt::format("  x[{}] -= H[{}] * x[{}];\n", i, i * n + j, j);
    }
  }
  return out + "}\n";
}

// One tape over the flat layout's inputs (q, q̇, q̈, t, parameters), with the intermediates
// and any derivative intermediates defined first.
Tape flat_tape(const System::Impl& s, const std::vector<GiNaC::ex>& outputs,
               const std::vector<std::pair<GiNaC::symbol, GiNaC::ex>>& extra) {
  std::vector<GiNaC::symbol> inputs;
  inputs.insert(inputs.end(), s.q.begin(), s.q.end());
  inputs.insert(inputs.end(), s.qd.begin(), s.qd.end());
  inputs.insert(inputs.end(), s.qdd.begin(), s.qdd.end());
  inputs.push_back(s.t);
  inputs.insert(inputs.end(), s.params.begin(), s.params.end());
  detail::TapeBuilder b(inputs, inputs.size() - s.params.size());
  detail::define_intermediates(b, s);
  for (const auto& [name, value] : extra) b.define(name, value);
  for (const GiNaC::ex& e : outputs) b.add_output(e);
  return b.build();
}

// The flat functions' text of the inputs: q, q_dot and q_ddot (or `qdd`, the local of
// forward_dynamics_derivatives), t = 0 (the system does not depend on it) and p.<name>.
Syntax flat_syntax(std::size_t nq, std::size_t n, const std::vector<std::string>& params,
                   std::string_view q_ddot, const std::string& pow_int) {
  Syntax syntax;
  for (std::size_t i = 0; i < nq; ++i) syntax.inputs.push_back(fmt::format("q[{}]", i));
  for (std::size_t i = 0; i < n; ++i) syntax.inputs.push_back(fmt::format("q_dot[{}]", i));
  for (std::size_t i = 0; i < n; ++i) syntax.inputs.push_back(fmt::format("{}[{}]", q_ddot, i));
  syntax.inputs.emplace_back("0.0");
  for (const std::string& p : params) syntax.inputs.push_back("p." + p);
  syntax.pow_int = pow_int;
  return syntax;
}

// τ = M q̈ − f in the symbols q̈: for a tree, its inverse dynamics in body coordinates plus
// what the rest of the system (a given Lagrangian, potentials, generalized forces) adds.
std::vector<GiNaC::ex> flat_tau(const System::Impl& s, const detail::TreeInverseDynamics& id) {
  const auto n = static_cast<std::size_t>(s.n);
  const bool tree = !id.tau.empty();
  std::vector<GiNaC::ex> tau(n);
  for (std::size_t i = 0; i < n; ++i) {
    GiNaC::ex e = tree ? id.tau[i] - (s.f[i] - s.tree_bias[i]).expand() : -s.f[i];
    for (std::size_t j = 0; j < n; ++j) {
      const GiNaC::ex& Mij = s.M[i * n + j];
      e += (tree ? (Mij - s.tree_M[i * n + j]).expand() : Mij) * s.qdd[j];
    }
    // expanded where there is no tree: a sum of products of sums compiled as it stands came out
    // in an order that changed from run to run
    tau[i] = tree ? e : e.expand();
  }
  return tau;
}

// The definitions inverse_dynamics' tape adds after the system's intermediates: the
// body-coordinate inverse dynamics'.
std::vector<std::pair<GiNaC::symbol, GiNaC::ex>> flat_definitions(
    const detail::TreeInverseDynamics& id) {
  std::vector<std::pair<GiNaC::symbol, GiNaC::ex>> out;
  for (std::size_t k = 0; k < id.aux.size(); ++k) out.emplace_back(id.aux[k], id.defs[k]);
  return out;
}

// The names the flat layout's own intermediates do not take (they are compiled, never
// printed: for legibility): the system's symbols and intermediates, and `more`.
std::set<std::string> taken_names(const System::Impl& s, const std::vector<GiNaC::symbol>& more) {
  std::set<std::string> taken(detail::reserved_names());
  for (const std::vector<std::string>* names : {&s.coord_names, &s.param_names}) {
    taken.insert(names->begin(), names->end());
  }
  for (const GiNaC::symbol& a : s.aux) taken.insert(a.get_name());
  for (const GiNaC::symbol& a : more) taken.insert(a.get_name());
  return taken;
}

// A tree's inverse dynamics in body coordinates (recursive.cpp), derived here, when the flat
// layout is asked for, rather than with every System; empty for an expanded derivation.
detail::TreeInverseDynamics body_coordinate_inverse_dynamics(const System::Impl& s) {
  if (s.tree_bodies.empty()) return {};
  return detail::tree_inverse_dynamics(s, s.tree_bodies, s.tree_gravity, taken_names(s, {}));
}

// M, f and ∂τ/∂(q, q̇) (n × 2n row-major) of flat_tau's τ, with the intermediates they read,
// for mass_matrix, forward_dynamics and the two derivative functions, so that the derivatives'
// q̈ and M are forward_dynamics' and mass_matrix's to the bit. A tree's own part comes from
// tree_inverse_dynamics_derivatives (closed form: ~40% of the operations of forward mode through
// the recursion's intermediates for a 7-joint arm, its M and f sharing them); what the rest of
// the system adds (springs, dampers, a given Lagrangian), and a system without a tree, by
// forward mode through the intermediates those terms read.
struct FlatDynamics {
  std::vector<std::pair<GiNaC::symbol, GiNaC::ex>> definitions;
  std::vector<GiNaC::ex> M, f, d;
};

FlatDynamics flat_dynamics(const System::Impl& s, const detail::TreeInverseDynamics& id,
                           const std::vector<GiNaC::ex>& tau) {
  const auto n = static_cast<std::size_t>(s.n);
  const auto nq = static_cast<std::size_t>(s.nq);
  std::vector<GiNaC::symbol> vars(s.q.begin(), s.q.end());
  vars.insert(vars.end(), s.qd.begin(), s.qd.end());
  if (id.tau.empty()) {
    detail::ForwardDerivatives D = detail::forward_derivatives(s.aux, s.aux_def, tau, vars);
    return {std::move(D.definitions), s.M, s.f, std::move(D.d)};
  }
  std::vector<GiNaC::ex> extra(n), extra_f(n), extra_M(n * n);
  for (std::size_t i = 0; i < n; ++i) {
    extra_f[i] = (s.f[i] - s.tree_bias[i]).expand();
    GiNaC::ex e = -extra_f[i];
    for (std::size_t j = 0; j < n; ++j) {
      extra_M[i * n + j] = (s.M[i * n + j] - s.tree_M[i * n + j]).expand();
      e += extra_M[i * n + j] * s.qdd[j];
    }
    extra[i] = e;
  }
  const detail::ForwardDerivatives D =
      detail::forward_derivatives(s.aux, s.aux_def, extra, vars);
  const detail::TreeDerivatives tree = detail::tree_inverse_dynamics_derivatives(
      s, s.tree_bodies, s.tree_gravity, taken_names(s, id.aux));
  FlatDynamics out;
  for (std::size_t k = 0; k < tree.aux.size(); ++k) {
    out.definitions.emplace_back(tree.aux[k], tree.defs[k]);
  }
  out.definitions.insert(out.definitions.end(), D.definitions.begin(), D.definitions.end());
  // D's columns are q's (nq) and the velocities'; a ball's tangent column k (q ⊗ exp(δθ), as
  // the tree's) is ∂/∂q · ∂q/∂δθ_k = ∂/∂q · ½ q ⊗ (0, e_k), the rate's coefficient of ω_k
  auto extra_d = [&](std::size_t i, std::size_t j) -> GiNaC::ex {
    const GiNaC::ex* row = &D.d[i * (nq + n)];
    if (j >= n) return row[nq + j - n];
    if (s.q_of_v[j] >= 0) return row[static_cast<std::size_t>(s.q_of_v[j])];
    GiNaC::ex sum = 0;
    for (const System::Impl::Ball& b : s.balls) {
      if (j < b.v || j >= b.v + 3) continue;
      for (std::size_t m = 0; m < 4; ++m) {
        if (!row[b.q + m].is_zero()) sum += row[b.q + m] * s.q_rate[b.q + m].diff(s.qd[j]);
      }
    }
    return sum;
  };
  out.d.resize(2 * n * n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < 2 * n; ++j) out.d[i * 2 * n + j] = (extra_d(i, j) + tree.d[i * 2 * n + j]).expand();
  }
  out.M.resize(n * n);
  for (std::size_t k = 0; k < n * n; ++k) out.M[k] = (tree.M[k] + extra_M[k]).expand();
  out.f.resize(n);
  for (std::size_t i = 0; i < n; ++i) out.f[i] = (-tree.tau_rest[i] + extra_f[i]).expand();
  return out;
}

// ∂q̈/∂x = −M⁻¹ ∂τ/∂x column by column and ∂q̈/∂τ = M⁻¹, each column one solve along the tree:
// O(n) stack, for the trees too large for the products. ∂τ/∂q and ∂τ/∂q̇ are the printer's
// outputs from `first`; closes the function.
std::string derivative_solves(const TapePrinter& printer, std::size_t first, std::size_t n,
                              const std::string& helpers) {
  std::string out = fmt::format("  double c[{}];\n", n);
  std::size_t k = first;
  for (const char* name : {"dq_ddot_dq", "dq_ddot_dq_dot"}) {
    for (std::size_t j = 0; j < n; ++j) {
      for (std::size_t i = 0; i < n; ++i) out += fmt::format("  c[{}] = -{};\n", i, printer.output(k + i * n + j));
      out += fmt::format("  {}::solve(H, c);\n", helpers);
      out += fmt::format("  for (int i = 0; i < {}; ++i) {}[i * {} + {}] = c[i];\n", n, name, n, j);
    }
    k += n * n;
  }
  out += fmt::format(
      "  for (int j = 0; j < {0}; ++j) {{\n"
      "    for (int i = 0; i < {0}; ++i) c[i] = i == j ? 1.0 : 0.0;\n"
      "    {1}::solve(H, c);\n"
      "    for (int i = 0; i < {0}; ++i) dq_ddot_dtau[i * {0} + j] = c[i];\n"
      "  }}\n}}\n",
      n, helpers);
  return out;
}

std::string flat_functions(const System::Impl& s, const std::vector<std::string>& params,
                           const std::string& helpers, std::size_t max_stack_bytes) {
  const auto n = static_cast<std::size_t>(s.n);
  const auto nq = static_cast<std::size_t>(s.nq);
  const detail::TreeInverseDynamics id = body_coordinate_inverse_dynamics(s);
  const std::vector<int> lambda = coordinate_tree(s);
  const std::string pow_int = helpers + "::pow_int";
  const std::vector<bool> none(nq + 2 * n + 1 + params.size(), false);
  // M's pairs (k, i), i = k or an ancestor of k: the entries factor() reads
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t k = 0; k < n; ++k) {
    pairs.emplace_back(k, k);
    for (std::size_t i : ancestors(lambda, k)) pairs.emplace_back(k, i);
  }
  std::string out;
  const std::vector<GiNaC::ex> tau = flat_tau(s, id);
  const FlatDynamics F = flat_dynamics(s, id, tau);

  // mass_matrix
  {
    const Tape tape = flat_tape(s, upper_triangle(F.M, n), F.definitions);
    const TapePrinter printer(tape, flat_syntax(nq, n, params, "q_ddot", pow_int));
    out += "/// M(q), nv × nv, row-major: the mass matrix (kinetic energy ½ q̇ᵀ M q̇).\n"
           "inline void mass_matrix([[maybe_unused]] const double* q, double* M, "
           "[[maybe_unused]] const Parameters& p = {}) {\n";
    out += printer.split_body("  ", none).first;
    std::size_t k = 0;
    out += symmetric_assignments(printer, k, "M", n);
    out += "}\n\n";
  }
  // inverse_dynamics
  {
    const Tape tape = flat_tape(s, tau, flat_definitions(id));
    const TapePrinter printer(tape, flat_syntax(nq, n, params, "q_ddot", pow_int));
    out += "/// τ = M(q) q̈ − f(q, q̇) (inverse dynamics): the joint forces that give the "
           "accelerations q̈.\n"
           "inline void inverse_dynamics([[maybe_unused]] const double* q, [[maybe_unused]] "
           "const double* q_dot,\n                             [[maybe_unused]] const double* "
           "q_ddot, double* tau,\n                             [[maybe_unused]] const "
           "Parameters& p = {}) {\n";
    out += printer.split_body("  ", none).first;
    for (std::size_t i = 0; i < n; ++i) out += fmt::format("  tau[{}] = {};\n", i, printer.output(i));
    out += "}\n\n";
  }
  // the part of forward_dynamics and its derivatives that factors M and solves for q̈
  auto solve_text = [&](const TapePrinter& printer, std::string_view on_failure) {
    std::string text = fmt::format("  double H[{}];\n", n * n);
    std::size_t k = 0;
    for (const auto& [r, c] : pairs) text += fmt::format("  H[{}] = {};\n", r * n + c, printer.output(k++));
    text += fmt::format("  double x[{}];\n", n);
    for (std::size_t i = 0; i < n; ++i) {
      text += fmt::format("  x[{}] = {} + tau[{}];\n", i, printer.output(k++), i);
    }
    text += fmt::format("  if (!{}::factor(H)) {{\n{}    return;\n  }}\n", helpers, on_failure);
    text += fmt::format("  {}::solve(H, x);\n", helpers);
    return text;
  };
  std::vector<GiNaC::ex> mass_and_forces;
  for (const auto& [r, c] : pairs) mass_and_forces.push_back(F.M[c * n + r]);
  mass_and_forces.insert(mass_and_forces.end(), F.f.begin(), F.f.end());
  // forward_dynamics
  {
    const Tape tape = flat_tape(s, mass_and_forces, F.definitions);
    const TapePrinter printer(tape, flat_syntax(nq, n, params, "q_ddot", pow_int));
    out += "/// q̈ = M(q)⁻¹ (f(q, q̇) + τ) (forward dynamics), M factored along the tree (factor()).\n"
           "/// Where M is not positive definite (a pivot ≤ 0: parameters no body can have) "
           "q_ddot is NaN.\n"
           "inline void forward_dynamics([[maybe_unused]] const double* q, [[maybe_unused]] "
           "const double* q_dot,\n                             const double* tau, double* "
           "q_ddot, [[maybe_unused]] const Parameters& p = {}) {\n";
    out += printer.split_body("  ", none).first;
    out += solve_text(printer, fmt::format("    for (int i = 0; i < {}; ++i) q_ddot[i] = std::nan(\"\");\n", n));
    out += fmt::format("  for (int i = 0; i < {}; ++i) q_ddot[i] = x[i];\n}}\n\n", n);
  }
  if (!s.balls.empty()) {
    // q̇ = ½ q ⊗ (0, ω) of each ball's quaternion, the velocities' entries for the others
    out += "/// dq/dt (nq) at (q, q̇): q̇'s entries, and ½ q ⊗ (0, ω) for a ball's quaternion (ω in its\n"
           "/// body's frame); the functions above take any q ≠ 0 for a quaternion, as the rotation "
           "q/|q|.\n"
           "inline void coordinate_rates(const double* q, const double* q_dot, double* q_rate) {\n";
    for (std::size_t v = 0; v < n; ++v) {
      if (s.q_of_v[v] >= 0) out += fmt::format("  q_rate[{}] = q_dot[{}];\n", s.q_of_v[v], v);
    }
    for (const System::Impl::Ball& b : s.balls) {
      const std::size_t w = b.q, x = b.q + 1, y = b.q + 2, z = b.q + 3;
      const std::size_t a = b.v, c = b.v + 1, e = b.v + 2;
      out += fmt::format("  q_rate[{}] = -0.5 * (q[{}] * q_dot[{}] + q[{}] * q_dot[{}] + q[{}] * q_dot[{}]);\n", w, x, a, y, c, z, e);
      out += fmt::format("  q_rate[{}] = 0.5 * (q[{}] * q_dot[{}] + q[{}] * q_dot[{}] - q[{}] * q_dot[{}]);\n", x, w, a, y, e, z, c);
      out += fmt::format("  q_rate[{}] = 0.5 * (q[{}] * q_dot[{}] + q[{}] * q_dot[{}] - q[{}] * q_dot[{}]);\n", y, w, c, z, a, x, e);
      out += fmt::format("  q_rate[{}] = 0.5 * (q[{}] * q_dot[{}] + q[{}] * q_dot[{}] - q[{}] * q_dot[{}]);\n", z, w, e, x, c, y, a);
    }
    out += "}\n\n";
  }
  auto dtau = [&](std::size_t i, std::size_t j) -> const GiNaC::ex& { return F.d[i * 2 * n + j]; };
  std::vector<GiNaC::ex> derivatives;
  for (std::size_t half = 0; half < 2; ++half) {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) derivatives.push_back(dtau(i, half * n + j));
  }
  // inverse_dynamics_derivatives
  {
    std::vector<GiNaC::ex> outputs = derivatives;
    for (const GiNaC::ex& e : upper_triangle(F.M, n)) outputs.push_back(e);
    const Tape tape = flat_tape(s, outputs, F.definitions);
    const TapePrinter printer(tape, flat_syntax(nq, n, params, "q_ddot", pow_int));
    out += "/// ∂τ/∂q, ∂τ/∂q̇ and ∂τ/∂q̈ = M of inverse_dynamics, nv × nv row-major each "
           "([i*nv + j] = ∂τ_i/∂x_j),\n/// exact (forward-mode differentiation of the same "
           "equations).\n"
           "inline void inverse_dynamics_derivatives([[maybe_unused]] const double* q,\n"
           "                                         [[maybe_unused]] const double* q_dot,\n"
           "                                         [[maybe_unused]] const double* q_ddot, "
           "double* dtau_dq,\n"
           "                                         double* dtau_dq_dot, double* "
           "dtau_dq_ddot,\n"
           "                                         [[maybe_unused]] const Parameters& p = {}) "
           "{\n";
    out += printer.split_body("  ", none).first;
    std::size_t k = 0;
    for (const char* name : {"dtau_dq", "dtau_dq_dot"}) {
      for (std::size_t i = 0; i < n * n; ++i) out += fmt::format("  {}[{}] = {};\n", name, i, printer.output(k++));
    }
    out += symmetric_assignments(printer, k, "dtau_dq_ddot", n);
    out += "}\n\n";
  }
  // forward_dynamics_derivatives: q̈ first, then ∂τ/∂(q, q̇) at that q̈ (the instructions that
  // read q̈ after the solve), then ∂q̈/∂x = −M⁻¹ ∂τ/∂x and ∂q̈/∂τ = M⁻¹, column by column
  {
    std::vector<GiNaC::ex> outputs = mass_and_forces;
    outputs.insert(outputs.end(), derivatives.begin(), derivatives.end());
    const Tape tape = flat_tape(s, outputs, F.definitions);
    const TapePrinter printer(tape, flat_syntax(nq, n, params, "qdd", pow_int));
    std::vector<bool> deferred(none);
    for (std::size_t i = 0; i < n; ++i) deferred[nq + n + i] = true;
    const auto [before, after] = printer.split_body("  ", deferred);
    out += "/// q̈ = forward_dynamics(q, q̇, τ) and its derivatives ∂q̈/∂q, ∂q̈/∂q̇, ∂q̈/∂τ = M⁻¹, "
           "nv × nv\n/// row-major each ([i*nv + j] = ∂q̈_i/∂x_j): ∂q̈/∂x = −M⁻¹ ∂τ/∂x at the "
           "q̈ found, τ = M q̈ − f.\n/// Where M is not positive definite every output is NaN.\n"
           "inline void forward_dynamics_derivatives([[maybe_unused]] const double* q,\n"
           "                                         [[maybe_unused]] const double* q_dot, "
           "const double* tau,\n"
           "                                         double* q_ddot, double* dq_ddot_dq, double* "
           "dq_ddot_dq_dot,\n"
           "                                         double* dq_ddot_dtau,\n"
           "                                         [[maybe_unused]] const Parameters& p = {}) "
           "{\n";
    out += before;
    out += solve_text(printer, fmt::format("    for (int i = 0; i < {}; ++i) q_ddot[i] = std::nan(\"\");\n"
                                           "    for (int i = 0; i < {}; ++i) {{\n"
                                           "      dq_ddot_dq[i] = dq_ddot_dq_dot[i] = dq_ddot_dtau[i] = std::nan(\"\");\n"
                                           "    }}\n", n, n * n));
    out += fmt::format("  [[maybe_unused]] const double* qdd = x;\n"
                       "  for (int i = 0; i < {}; ++i) q_ddot[i] = x[i];\n", n);
    out += after;
    // M⁻¹ by n solves along the tree, then the two products −M⁻¹ ∂τ/∂x as plain loops (the
    // compiler vectorises them; 2n more solves would each be a chain of dependent steps). The
    // two n × n locals and c take 16 n² + 8 n bytes of stack; beyond max_stack_bytes, 2n more
    // solves instead.
    if (16 * n * n + 8 * n > max_stack_bytes) {
      out += derivative_solves(printer, pairs.size() + n, n, helpers);
      return out;
    }
    out += fmt::format(
        "  double Mi[{0}], c[{1}], D[{0}];\n"
        "  for (int j = 0; j < {1}; ++j) {{\n"
        "    for (int i = 0; i < {1}; ++i) c[i] = i == j ? 1.0 : 0.0;\n"
        "    {2}::solve(H, c);\n"
        "    for (int i = 0; i < {1}; ++i) Mi[i * {1} + j] = c[i];\n"
        "  }}\n"
        "  for (int i = 0; i < {0}; ++i) dq_ddot_dtau[i] = Mi[i];\n",
        n * n, n, helpers);
    std::size_t k = pairs.size() + n;
    for (const char* name : {"dq_ddot_dq", "dq_ddot_dq_dot"}) {
      for (std::size_t i = 0; i < n * n; ++i) out += fmt::format("  D[{}] = {};\n", i, printer.output(k + i));
      out += fmt::format(
          "  for (int i = 0; i < {0}; ++i) {{\n"
          "    double row[{0}] = {{}};\n"
          "    for (int l = 0; l < {0}; ++l) {{\n"
          "      for (int j = 0; j < {0}; ++j) row[j] -= Mi[i * {0} + l] * D[l * {0} + j];\n"
          "    }}\n"
          "    for (int j = 0; j < {0}; ++j) {1}[i * {0} + j] = row[j];\n"
          "  }}\n",
          n, name);
      k += n * n;
    }
    out += "}\n";
  }
  return out;
}

}  // namespace

Language parse_language(std::string_view name) {
  if (name == "c++" || name == "cpp" || name == "cxx" || name == "C++") return Language::kCpp;
  if (name == "python" || name == "py") return Language::kPython;
  const std::vector<std::string> known = {"c++", "python", "cpp", "py"};
  throw Error(fmt::format("unknown export language '{}'; expected c++ or python{}", name,
                          did_you_mean_hint(name, known)));
}

namespace {

// The exported functions hold M, f and the holonomic rows G, γ; velocity constraints would be
// missing from them without a word, so such a system is refused.
const System::Impl& exportable(const System& system) {
  if (system.num_velocity_constraints() > 0) {
    throw Error(fmt::format("the system has velocity constraints ({}); the export writes M, f and "
                            "the holonomic constraints' G and gamma only",
                            fmt::join(system.velocity_constraint_names(), ", ")));
  }
  return impl_of(system);
}

}  // namespace

// The namespaced C++ and the Python export write q̇ = dq/dt; a ball coordinate's velocity is its
// ω, which only the flat layout writes.
void refuse_balls_unless_flat(const System::Impl& s) {
  if (s.balls.empty()) return;
  throw Error(fmt::format("the code export of a system with ball coordinates (here '{}': a ball or "
                          "free joint) writes the flat C++ layout only (--flat): the namespaced C++ "
                          "and the Python functions take the velocities as dq/dt, and a ball's is "
                          "its angular velocity",
                          s.balls.front().name));
}

// The flat layout: no namespace, no t, the dynamics and their derivatives (export.hpp).
std::string emit_cpp_flat(const System::Impl& s, const ExportOptions& options) {
  if (s.m > 0) {
    throw Error(fmt::format("the flat C++ layout exports the dynamics of a system without "
                            "constraints; this one has {} ({}): export it without --flat",
                            s.m, fmt::join(s.constraint_names, ", ")));
  }
  const auto time_dependent = [&](const std::vector<GiNaC::ex>& es) {
    return std::any_of(es.begin(), es.end(), [&](const GiNaC::ex& e) { return e.has(s.t); });
  };
  if (time_dependent(s.M) || time_dependent(s.f) || time_dependent(s.aux_def)) {
    throw Error("the flat C++ layout exports functions of (q, q_dot) without the time t, and "
                "this system's equations depend on t: export it without --flat");
  }
  const std::vector<std::string> params =
      export_identifiers(s.param_names, Language::kCpp, Scope::kMember);
  const std::string helpers =
      export_identifiers({options.name + "_detail"}, Language::kCpp, Scope::kNamespace)[0];
  const std::string& ns = options.flat_namespace;
  if (!ns.empty()) {
    // the user's name as written, or refused: a renamed namespace would not be the one asked for
    const std::string id = export_identifiers({ns}, Language::kCpp, Scope::kNamespace)[0];
    if (id != ns) {
      throw Error(fmt::format("the namespace '{}' is not a C++ identifier the export may take "
                              "(letters, digits and '_', not starting with a digit or '_', not a "
                              "keyword, 'std', a macro or a name <cmath> declares): '{}' would be",
                              ns, id));
    }
  }
  std::string out = header_comment(
      s, options, "//", renamed(s.param_names, params),
      "a name starting with '_' takes a 'p' in front; a C or C++ keyword or a macro of the "
      "compiler or <cmath> takes '_' at the end until unused");
  std::string layout = s.balls.empty()
             ? "//\n// The dynamics M(q) q̈ = f(q, q̇) + τ at global scope (no namespace, no t): "
               "nq = nv coordinates,\n// arrays row-major ([i*nv + j]), parameters as defaults "
               "(forward_dynamics(q, q_dot, tau, q_ddot, {.name = value})).\n"
               "// forward_dynamics factors M along the tree of the coordinates (no dense "
               "factorization where\n// the tree makes M sparse); the derivatives are exact.\n"
             : "//\n// The dynamics M(q) v̇ = f(q, v) + τ at global scope (no namespace, no t): q "
               "has nq entries\n// (a ball's unit quaternion w x y z among them), the velocities "
               "v (q_dot) nv (a ball's ω in\n// its body's frame; dq/dt by coordinate_rates); "
               "arrays row-major ([i*nv + j]), parameters as\n// defaults. forward_dynamics "
               "factors M along the tree of the coordinates. The derivatives are exact;\n// a "
               "ball's columns of d/dq are along its tangent, q ⊗ exp(δθ) with δθ in its body's "
               "frame\n// (MuJoCo's convention), so that every derivative is nv × nv.\n";
  if (!ns.empty()) {
    // in namespace ns (--namespace): the same text otherwise
    const std::string global = "at global scope (no namespace, no t)";
    layout.replace(layout.find(global), global.size(), fmt::format("in namespace {} (no t)", ns));
  }
  out += layout;
  out += "#pragma once\n\n#include <cmath>\n\n";
  if (!ns.empty()) out += fmt::format("namespace {} {{\n\n", ns);
  out += fmt::format("inline constexpr int nq = {};  // configuration entries\n", s.nq);
  out += fmt::format("inline constexpr int nv = {};  // velocity entries\n", s.n);
  std::vector<std::string> names;
  for (const auto& c : s.coord_names) names.push_back(quoted(c));
  out += fmt::format("inline constexpr const char* coordinate_names[] = {{{}}};\n",
                     fmt::join(names, ", "));
  if (!s.balls.empty()) {
    names.clear();
    for (const auto& c : s.velocity_names) names.push_back(quoted(c));
    out += fmt::format("inline constexpr const char* velocity_names[] = {{{}}};\n", fmt::join(names, ", "));
  }
  out += "\n/// The model's parameters (SI), defaults as in the model.\n";
  out += cpp_parameters(s, params);
  out += fmt::format("\nnamespace {} {{\n", helpers);
  out += kCppPowInt;
  out += "\n";
  out += flat_factor_and_solve(coordinate_tree(s));
  out += fmt::format("}}  // namespace {}\n\n", helpers);
  out += flat_functions(s, params, helpers, options.max_stack_bytes);
  if (!ns.empty()) out += fmt::format("\n}}  // namespace {}\n", ns);
  return out;
}

std::string emit_cpp(const System& system, const ExportOptions& options) {
  detail::SymbolicLock lock;  // the functions' tapes are compiled from the expressions
  const System::Impl& s = exportable(system);
  if (options.flat) return emit_cpp_flat(s, options);
  refuse_balls_unless_flat(s);
  const std::vector<std::string> params =
      export_identifiers(s.param_names, Language::kCpp, Scope::kMember);
  const std::string ns = export_identifiers({options.name}, Language::kCpp, Scope::kNamespace)[0];
  std::vector<std::string> renames = renamed(s.param_names, params);
  if (ns != options.name) renames.push_back(fmt::format("namespace {} → {}", options.name, ns));
  std::string out = header_comment(
      s, options, "//", renames,
      "a name starting with '_' takes a 'p' in front; a C or C++ keyword, a macro of the "
      "compiler or <cmath>, and for the namespace main or a name <cmath> declares, take '_' at "
      "the end until unused");
  out += "//\n// Arrays are row-major: M[i*n + j], G[k*n + i]. Parameters are named arguments with\n"
         "// the model's values as defaults: forces(q, q_dot, t, f, {.name = value}).\n";
  out += "#pragma once\n\n#include <cmath>\n\n";
  out += fmt::format("namespace {} {{\n\n", ns);
  out += fmt::format("inline constexpr int kNumCoordinates = {};\n", s.n);
  out += fmt::format("inline constexpr int kNumConstraints = {};\n", s.m);
  std::vector<std::string> names;
  for (const auto& c : s.coord_names) names.push_back(quoted(c));
  out += fmt::format("inline constexpr const char* kCoordinateNames[] = {{{}}};\n", fmt::join(names, ", "));
  if (s.m > 0) {
    names.clear();
    for (const auto& c : s.constraint_names) names.push_back(quoted(c));
    out += fmt::format("inline constexpr const char* kConstraintNames[] = {{{}}};\n", fmt::join(names, ", "));
  }
  out += "\n/// The model's parameters (SI), defaults as in the model";
  out += params != s.param_names ? "; the renamed ones (see above) name the model's in a comment.\n"
                                 : ".\n";
  out += cpp_parameters(s, params);
  out += "\nnamespace detail {\n";
  out += kCppPowInt;
  out += "}  // namespace detail\n";
  for (const FunctionSpec& fn : kFunctions) {
    out += "\n";
    out += cpp_function(s, fn, params);
  }
  out += "\n";
  out += cpp_dynamics(s);
  out += fmt::format("\n}}  // namespace {}\n", ns);
  return out;
}

std::string emit_python(const System& system, const ExportOptions& options) {
  detail::SymbolicLock lock;  // the functions' tapes are compiled from the expressions
  const System::Impl& s = exportable(system);
  refuse_balls_unless_flat(s);
  const std::vector<std::string> params =
      export_identifiers(s.param_names, Language::kPython, Scope::kMember);
  std::string out = header_comment(s, options, "#", renamed(s.param_names, params),
                                   "a name starting with '_' takes a 'p' in front; a Python "
                                   "keyword or a name the module uses takes '_' at the end until "
                                   "unused");
  out += "#\n# Matrices are lists of rows. Parameters are keyword arguments with the model's values\n"
         "# as defaults: forces(q, q_dot, t, m1=2.0).\n";
  out += "import math\n\n";
  std::vector<std::string> names;
  for (const auto& c : s.coord_names) names.push_back(quoted(c));
  out += fmt::format("COORDINATES = ({}{})\n", fmt::join(names, ", "), names.size() == 1 ? "," : "");
  names.clear();
  for (const auto& c : s.constraint_names) names.push_back(quoted(c));
  out += fmt::format("CONSTRAINTS = ({}{})\n", fmt::join(names, ", "), names.size() == 1 ? "," : "");
  std::vector<std::string> items, renames;
  for (std::size_t k = 0; k < params.size(); ++k) {
    items.push_back(fmt::format("{}: {}", quoted(s.param_names[k]), literal(s.param_values[k], true)));
    renames.push_back(fmt::format("{}: {}", quoted(s.param_names[k]), quoted(params[k])));
  }
  out += fmt::format("PARAMETERS = {{{}}}\n", fmt::join(items, ", "));
  out += "# the keyword argument of each parameter (its name unless that is reserved)\n";
  out += fmt::format("PARAMETER_NAMES = {{{}}}\n\n\n", fmt::join(renames, ", "));
  out += "def _vector(values, size, name):\n"
         "    values = [float(v) for v in values]\n"
         "    if len(values) != size:\n"
         "        raise ValueError(f\"{name} needs {size} values (one per coordinate), got {len(values)}\")\n"
         "    return values\n\n\n"
         "def _pow_int(x, k):\n"
         "    \"\"\"x**k (k >= 1) by binary powering, as the engine computes it.\"\"\"\n"
         "    v = 1.0\n"
         "    while k > 0:\n"
         "        if k & 1:\n"
         "            v *= x\n"
         "        x *= x\n"
         "        k >>= 1\n"
         "    return v\n";
  for (const FunctionSpec& fn : kFunctions) {
    out += "\n\n";
    out += python_function(s, fn, params);
  }
  out += "\n\n";
  out += python_dynamics(s, params);
  return out;
}

std::string export_namespace(const std::string& name) {
  return export_identifiers({name}, Language::kCpp, Scope::kNamespace)[0];
}

std::string emit(const System& system, Language language, const ExportOptions& options) {
  return language == Language::kCpp ? emit_cpp(system, options) : emit_python(system, options);
}

void constraint_terms(const System& system, Workspace& ws, double t, const Eigen::VectorXd& q,
                      const Eigen::VectorXd& q_dot, Eigen::MatrixXd& G, Eigen::VectorXd& gamma) {
  const System::Impl& s = impl_of(system);
  s.refuse_balls("constraint terms");
  Workspace::Impl* w = Workspace::Access::impl(ws);
  RIGID_REQUIRE(w != nullptr && w->owner == &s,
                "the workspace belongs to another System (or was moved from); make one with "
                "this System's make_workspace()");
  RIGID_REQUIRE(q.size() == s.n && q_dot.size() == s.n,
                "expected q and q_dot of size {} (one per coordinate), got {} and {}", s.n,
                q.size(), q_dot.size());
  const auto n = static_cast<std::size_t>(s.n);
  for (std::size_t i = 0; i < n; ++i) {
    w->in[i] = q[static_cast<Eigen::Index>(i)];
    w->in[n + i] = q_dot[static_cast<Eigen::Index>(i)];
  }
  w->in[2 * n] = t;
  std::copy(w->params.begin(), w->params.end(), w->in.begin() + static_cast<std::ptrdiff_t>(2 * n + 1));
  s.dyn.evaluate(w->in.data(), w->out.data(), w->dyn_scratch);
  // the dynamics tape's outputs: M's upper triangle, f, G (m × n), γ (m), ġ, g
  std::size_t k = n * (n + 1) / 2 + n;
  G.resize(s.m, s.n);
  gamma.resize(s.m);
  for (int a = 0; a < s.m; ++a)
    for (int i = 0; i < s.n; ++i) G(a, i) = w->out[k++];
  for (int a = 0; a < s.m; ++a) gamma[a] = w->out[k++];
}

}  // namespace rigid::lagrange
