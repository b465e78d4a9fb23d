// Fuzz target: a run's schema as summary.json carries it (rigid::io::parse_schema_json, what
// `rigid report DIR` reads). A schema that is read must write back to text that reads to the
// same schema (the round trip is exact); anything else is a refusal naming the source.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "fuzz_support.hpp"
#include "rigid/io/run_schema.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input = rigid::fuzz::as_text(data, size);
  rigid::fuzz::refuse_or_return(input, [&] {
    const rigid::io::RunSchema schema = rigid::io::parse_schema_json(input, "summary.json");
    if (rigid::io::parse_schema_json(rigid::io::schema_json(schema), "round trip") != schema) {
      std::fprintf(stderr, "rigid fuzz: the schema does not read back as written\n");
      std::abort();
    }
  });
  return 0;
}
