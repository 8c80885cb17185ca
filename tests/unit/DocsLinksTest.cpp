// The README is the way into the documentation: it links every page under docs/, and every page
// it links exists (docs/choosing.md is written by `penumbra bench`, so a run that was not
// committed shows here).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

const fs::path kRepository = fs::path(PENUMBRA_TEST_DATA).parent_path().parent_path();

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(DocsLinks, ReadmeLinksEveryDocsPageAndEveryLinkedPageExists) {
  const std::string readme = slurp(kRepository / "README.md");
  ASSERT_FALSE(readme.empty()) << kRepository / "README.md";
  size_t pages = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(kRepository / "docs")) {
    if (e.path().extension() != ".md") continue;
    ++pages;
    const std::string link = "](docs/" + e.path().filename().string();
    EXPECT_NE(readme.find(link), std::string::npos) << "README.md does not link docs/" << e.path().filename().string();
  }
  EXPECT_GT(pages, 0u);
  const std::regex local(R"(\]\((docs/[^)#\s]+))");
  size_t links = 0;
  for (std::sregex_iterator it(readme.begin(), readme.end(), local), end; it != end; ++it) {
    ++links;
    EXPECT_TRUE(fs::exists(kRepository / (*it)[1].str())) << "README.md links " << (*it)[1].str() << ", which does not exist";
  }
  EXPECT_GE(links, pages);
}
