// Fuzz target: the URDF/MJCF/SDF <inertial> reader. Every entry it accepts is validated, and
// an accepted entry must survive the writer and the reader again: written as the same format
// (tensor in the link frame) and read back, mass, COM and inertia agree to a few ulps of
// their size (the writer prints shortest round-trip decimals; the only rounding is the
// reader's rotation by an identity rpy/quat, which is exact, and the check's own 1e-12).
#include <algorithm>
#include <cmath>
#include <string>

#include "fuzz_support.hpp"
#include "rigid/io/inertial_xml.hpp"

namespace {

void check_round_trip(const rigid::MassProperties& mp, rigid::io::InertialFormat format) {
  const std::string doc = rigid::io::write_inertial_document(mp, format);
  const auto again = rigid::io::read_inertials(doc, "round-trip");
  const double scale = std::max({1.0, std::abs(mp.mass()), mp.com().cwiseAbs().maxCoeff(),
                                 mp.inertia_com().cwiseAbs().maxCoeff()});
  const double tol = 1e-12 * scale;
  const bool same = again.size() == 1 && !again[0].problem &&
                    std::abs(again[0].mass - mp.mass()) <= tol &&
                    (again[0].com - mp.com()).cwiseAbs().maxCoeff() <= tol &&
                    (again[0].inertia_com - mp.inertia_com()).cwiseAbs().maxCoeff() <= tol;
  if (!same) {
    std::fprintf(stderr, "rigid fuzz: %s inertial does not survive write + read:\n%s\n",
                 rigid::io::to_string(format), doc.c_str());
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input = rigid::fuzz::as_text(data, size);
  const std::string xml(input);
  rigid::fuzz::refuse_or_return(input, [&] {
    const auto format = rigid::io::detect_inertial_format(xml, "fuzz.xml");
    for (const auto& entry : rigid::io::read_inertials(xml, "fuzz.xml")) {
      if (entry.problem) {
        rigid::fuzz::refuse_or_return(input, [&] { (void)entry.mass_properties(); });
        continue;
      }
      const rigid::MassProperties mp = entry.mass_properties();
      (void)mp.principal_axes();
      check_round_trip(mp, format);
    }
  });
  return 0;
}
