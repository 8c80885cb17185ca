// The README is the way into the documentation: it links every page under docs/, and every page
// it links exists (docs/choosing.md is written by `penumbra bench`, so a run that was not
// committed shows here). Links to a part of a page name a heading that page has.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

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

namespace {

// A heading's anchor as GitHub makes it: lower case, every character but letters, digits, spaces,
// hyphens and underscores dropped (non-ASCII ones too: no link here names a heading by such a
// character), spaces to hyphens.
std::string anchorOf(const std::string& heading) {
  std::string out;
  for (unsigned char c : heading) {
    if (std::isalnum(c) || c == '-' || c == '_') out += static_cast<char>(std::tolower(c));
    else if (c == ' ') out += '-';
  }
  return out;
}

// The anchors of a Markdown page: its headings' (outside code blocks; a repeated one gets -1,
// -2, … as GitHub numbers them) and its explicit <a id="…">s.
std::set<std::string> anchorsOf(const std::string& page) {
  std::set<std::string> anchors;
  std::map<std::string, int> seen;
  std::istringstream lines(page);
  bool code = false;
  for (std::string line; std::getline(lines, line);) {
    if (line.starts_with("```")) code = !code;
    if (code || !line.starts_with("#")) continue;
    const size_t text = line.find_first_not_of('#');
    if (text == std::string::npos || line[text] != ' ') continue;
    const std::string anchor = anchorOf(line.substr(text + 1));
    const int n = seen[anchor]++;
    anchors.insert(n == 0 ? anchor : anchor + "-" + std::to_string(n));
  }
  const std::regex id(R"(<a id="([^"]+)\")");
  for (std::sregex_iterator it(page.begin(), page.end(), id), end; it != end; ++it) anchors.insert((*it)[1].str());
  return anchors;
}

}  // namespace

// Every link from one page to a part of another (or of itself), page.md#part, names a heading or
// an <a id> that the page has: a renamed section breaks no link unnoticed.
TEST(DocsLinks, EveryLinkToAPartOfAPageNamesOneItHas) {
  std::vector<fs::path> pages = {kRepository / "README.md"};
  for (const fs::directory_entry& e : fs::directory_iterator(kRepository / "docs"))
    if (e.path().extension() == ".md") pages.push_back(e.path());
  const std::regex link(R"(\]\(([^)#\s]*)#([^)\s]+)\))");
  size_t checked = 0;
  std::map<fs::path, std::set<std::string>> anchors;  // per page, read once
  for (const fs::path& page : pages) {
    const std::string text = slurp(page);
    for (std::sregex_iterator it(text.begin(), text.end(), link), end; it != end; ++it) {
      const std::string target = (*it)[1].str(), part = (*it)[2].str();
      if (target.find("://") != std::string::npos) continue;
      const fs::path targetPath = target.empty() ? page : page.parent_path() / target;
      if (targetPath.extension() != ".md") continue;
      ASSERT_TRUE(fs::exists(targetPath)) << page.filename() << " links " << target << ", which does not exist";
      ++checked;
      const fs::path key = fs::weakly_canonical(targetPath);
      if (!anchors.contains(key)) anchors[key] = anchorsOf(slurp(key));
      EXPECT_TRUE(anchors[key].contains(part))
          << page.filename() << " links " << target << "#" << part << ", which names no heading there";
    }
  }
  EXPECT_GT(checked, 50u);
}
