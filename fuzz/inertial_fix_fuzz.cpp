// Fuzz target: `rigid inertia fix` on a URDF/MJCF/SDF document (the geometry readers of links
// and bodies, MJCF defaults and orientations, the byte-position rewrite). A document it fixes
// must fix again: the rewritten text parses and fixing it gives the same links with the same
// new inertials, bit for bit (the geometry did not change; an MJCF body now keeps the
// inertial that was written, read back exactly).
#include <string>

#include "fuzz_support.hpp"
#include "rigid/io/inertial_fix.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input = rigid::fuzz::as_text(data, size);
  const std::string xml(input);
  rigid::fuzz::refuse_or_return(input, [&] {
    // a name no file has: relative mesh paths resolve to nothing on disk
    const auto result = rigid::io::fix_inertials(xml, "/nonexistent-rigid-fuzz/model.xml");
    if (!result.ok()) return;
    const auto again = rigid::io::fix_inertials(result.text, "/nonexistent-rigid-fuzz/model.xml");
    // the geometry is the same, so are the new inertials, bit for bit
    bool same = again.ok() && again.links.size() == result.links.size();
    // (or, where MJCF's inertiafromgeom="auto" now keeps the written inertial, it reads back
    // as written: shortest round-trip decimals)
    for (std::size_t i = 0; same && i < result.links.size(); ++i) {
      const auto& a = result.links[i].fixed;
      if (!a) continue;
      const auto& b = again.links[i];
      if (b.fixed) {
        same = a->mass() == b.fixed->mass() && a->com() == b.fixed->com() &&
               a->inertia_com() == b.fixed->inertia_com();
      } else {
        same = b.old && !b.old->problem && a->mass() == b.old->mass && a->com() == b.old->com &&
               (a->inertia_com() - b.old->inertia_com).cwiseAbs().maxCoeff() == 0;
      }
    }
    if (!same) {
      std::fprintf(stderr, "rigid fuzz: the fixed document does not fix again:\n%s\n",
                   result.text.c_str());
      std::abort();
    }
  });
  return 0;
}
