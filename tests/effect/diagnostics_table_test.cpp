// docs/diagnostics.md is the one list of diagnostic codes: every code the assembler and
// the effect reader can report has a row in its section, and every row of those
// sections is a code their sources report.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

const std::string kRoot = std::string(REFX_TEST_DIR) + "/..";

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in) << "cannot read " << path;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Codes matching `pattern` in quotes ("A2001") in the given source files.
std::set<std::string> codesInSources(const std::vector<std::string>& files, const std::string& pattern) {
  std::set<std::string> codes;
  const std::regex quoted("\"(" + pattern + ")\"");
  for (const std::string& f : files) {
    const std::string text = readText(kRoot + "/" + f);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), quoted); it != std::sregex_iterator(); ++it)
      codes.insert((*it)[1].str());
  }
  return codes;
}

// First-column codes of the table rows under the "## heading" section of the docs.
std::set<std::string> codesInSection(const std::string& heading) {
  const std::string docs = readText(kRoot + "/docs/diagnostics.md");
  const size_t start = docs.find("\n## " + heading + "\n");
  EXPECT_NE(start, std::string::npos) << "no section '" << heading << "'";
  if (start == std::string::npos) return {};
  size_t end = docs.find("\n#", start + 1);
  if (end == std::string::npos) end = docs.size();
  const std::string section = docs.substr(start, end - start);
  std::set<std::string> codes;
  static const std::regex row(R"(\n\| ([A-Z][0-9]{4}) \|)");
  for (auto it = std::sregex_iterator(section.begin(), section.end(), row); it != std::sregex_iterator(); ++it)
    codes.insert((*it)[1].str());
  return codes;
}

void expectSame(const std::set<std::string>& sources, const std::set<std::string>& docs) {
  for (const std::string& c : sources) EXPECT_TRUE(docs.count(c)) << c << " is reported but has no row";
  for (const std::string& c : docs) EXPECT_TRUE(sources.count(c)) << c << " has a row but is never reported";
}

TEST(DiagnosticsTable, AssemblerCodesHaveRowsAndRowsHaveCodes) {
  const std::set<std::string> sources = codesInSources({"src/shader/assembler.cpp"}, "A[0-9]{4}");
  EXPECT_GE(sources.size(), 10u);  // the pattern found the codes at all
  expectSame(sources, codesInSection("Assembler (A2xxx)"));
}

TEST(DiagnosticsTable, EffectCodesHaveRowsAndRowsHaveCodes) {
  const std::set<std::string> sources = codesInSources(
      {"src/effect/lexer.cpp", "src/effect/parser.cpp", "src/effect/effect.cpp"}, "F[0-9]{4}");
  EXPECT_GE(sources.size(), 10u);
  expectSame(sources, codesInSection("Effect files (F1xxx)"));
}

}  // namespace
