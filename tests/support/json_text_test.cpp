// The test helpers' JSON reading: a document, a refusal, a missing file.
#include "json_text.h"

#include <gtest/gtest.h>

#include <fstream>

namespace periflex::testing {
namespace {

TEST(JsonText, ParsesADocumentAndThrowsOnText) {
  const auto j = parse_json(R"({"frames_written": 101, "ok": true})");
  EXPECT_EQ(j["frames_written"].get<long>(), 101);
  EXPECT_THROW(parse_json("{not json"), nlohmann::json::parse_error);
}

TEST(JsonText, AFileThatIsMissingOrBrokenReadsAsDiscarded) {
  const auto dir = std::filesystem::temp_directory_path() / "periflex_json_text_test";
  std::filesystem::create_directories(dir);
  EXPECT_TRUE(read_json_file(dir / "missing.json").is_discarded());
  std::ofstream(dir / "broken.json") << "{\"a\": ";
  EXPECT_TRUE(read_json_file(dir / "broken.json").is_discarded());
  std::ofstream(dir / "whole.json") << "{\"a\": 2.5}";
  EXPECT_EQ(read_json_file(dir / "whole.json")["a"].get<double>(), 2.5);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace periflex::testing
