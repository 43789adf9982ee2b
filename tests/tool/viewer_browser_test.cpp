// The viewer in a real browser: Debian's chromium, headless, opens a page `softstep view` wrote
// for a small scene at a given frame. The page must report that it drew that frame with no
// script error, the browser must log no console message, and its screenshot must show the
// scene (coloured joints in the 3D view), not a blank canvas. Skipped, with the reason, when
// chromium is not installed (.ci/setup installs it).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>

#include "png_reader.hpp"
#include "run_tool.hpp"

namespace softstep::tool_test {
namespace {

std::string find_chromium() {
  if (const char* env = std::getenv("SOFTSTEP_CHROMIUM")) return env;
  for (const char* path : {"/usr/bin/chromium", "/usr/bin/chromium-browser"}) {
    if (std::filesystem::exists(path)) return path;
  }
  return "";
}

struct BrowserRun {
  int exit_code = -1;
  std::string out, log;
};

// The flags this machine kind documents for headless chromium, a fresh profile each run, and
// the console logged to stderr.
BrowserRun run_chromium(const std::string& chromium, const std::string& dir,
                        const std::string& what, const std::string& url) {
  static int runs = 0;
  const std::string profile = dir + "/profile" + std::to_string(runs++);
  const std::string command =
      "timeout 120 " + chromium +
      " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run"
      " --disable-background-networking --disable-component-update --disable-sync"
      " --user-data-dir=" +
      profile + " --enable-logging=stderr --v=0 --window-size=1280,720 --hide-scrollbars " + what +
      " '" + url + "' > " + dir + "/browser.out 2> " + dir + "/browser.log";
  BrowserRun run;
  run.exit_code = std::system(command.c_str());
  run.out = read_text(dir + "/browser.out");
  run.log = read_text(dir + "/browser.log");
  return run;
}

// What the page says about itself once its script ran: <body data-state=... data-frame=...>.
std::string body_attribute(const std::string& dom, const std::string& name) {
  std::smatch m;
  if (!std::regex_search(dom, m, std::regex("<body[^>]*\\s" + name + "=\"([^\"]*)\"")))
    return "(no " + name + ")";
  return m[1];
}

// Console messages and uncaught exceptions the browser logged.
std::vector<std::string> console_lines(const std::string& log) {
  std::vector<std::string> lines;
  std::size_t at = 0;
  while (at < log.size()) {
    const std::size_t end = std::min(log.find('\n', at), log.size());
    const std::string line = log.substr(at, end - at);
    if (line.find(":CONSOLE") != std::string::npos || line.find("Uncaught") != std::string::npos)
      lines.push_back(line);
    at = end + 1;
  }
  return lines;
}

// Pixels of the 3D view (left of the 380 px side panel) away from the background, and those
// of them with a clear colour (joints are coloured; bodies and text are grey or white).
struct Drawn {
  long different = 0, coloured = 0;
};
Drawn drawn_in_view(const Image& image) {
  const std::uint8_t* background = image.pixel(image.width / 2, image.height - 2);
  Drawn d;
  for (int y = 40; y < image.height; ++y) {  // below the text in the corner
    for (int x = 0; x < image.width - 400; ++x) {
      const std::uint8_t* p = image.pixel(x, y);
      int distance = 0;
      for (int k = 0; k < 3; ++k) distance += std::abs(int(p[k]) - int(background[k]));
      if (distance < 30) continue;
      ++d.different;
      const int hi = std::max({p[0], p[1], p[2]}), lo = std::min({p[0], p[1], p[2]});
      if (hi - lo > 60) ++d.coloured;
    }
  }
  return d;
}

TEST(ViewerInBrowser, DrawsTheSceneAtTheAskedFrameWithoutErrors) {
  const std::string chromium = find_chromium();
  if (chromium.empty()) GTEST_SKIP() << "chromium is not installed (.ci/setup installs it)";
  const std::string dir = scratch_dir("viewer_browser");
  const ToolRun view = run_tool(
      "view chain --links 30 --chains 4 --hertz 3 --zeta 0.2 --steps 120 "
      "--out " +
      dir + "/page");
  ASSERT_EQ(view.exit_code, 0) << view.err;
  const std::string url = "file://" + dir + "/page/index.html#frame=40";

  const BrowserRun dom = run_chromium(chromium, dir, "--dump-dom", url);
  ASSERT_EQ(dom.exit_code, 0) << dom.log;
  EXPECT_EQ(body_attribute(dom.out, "data-state"), "ready");
  EXPECT_EQ(body_attribute(dom.out, "data-frame"), "40");
  EXPECT_EQ(body_attribute(dom.out, "data-errors"), "0");
  EXPECT_EQ(console_lines(dom.log), std::vector<std::string>{});

  const BrowserRun shot = run_chromium(chromium, dir, "--screenshot=" + dir + "/shot.png", url);
  ASSERT_EQ(shot.exit_code, 0) << shot.log;
  EXPECT_EQ(console_lines(shot.log), std::vector<std::string>{});
  const Image image = read_png(dir + "/shot.png");
  EXPECT_EQ(image.width, 1280);
  const Drawn drawn = drawn_in_view(image);
  EXPECT_GT(drawn.different, 500) << "the 3D view is blank";
  EXPECT_GT(drawn.coloured, 100) << "no coloured joints in the 3D view";
  if (const char* keep = std::getenv("SOFTSTEP_VIEWER_SCREENSHOT"))
    std::filesystem::copy_file(dir + "/shot.png", keep,
                               std::filesystem::copy_options::overwrite_existing);
}

// The checks above can fail: a blank page is judged blank, and a page whose script throws is
// seen to throw.
TEST(ViewerInBrowser, TheChecksSeeABlankPageAndAScriptError) {
  const std::string chromium = find_chromium();
  if (chromium.empty()) GTEST_SKIP() << "chromium is not installed (.ci/setup installs it)";
  const std::string dir = scratch_dir("viewer_browser_controls");
  {
    std::ofstream(dir + "/blank.html")
        << "<!doctype html><html><body style=\"background:#101114\"></body></html>";
  }
  const BrowserRun blank = run_chromium(chromium, dir, "--screenshot=" + dir + "/blank.png",
                                        "file://" + dir + "/blank.html");
  ASSERT_EQ(blank.exit_code, 0) << blank.log;
  const Drawn drawn = drawn_in_view(read_png(dir + "/blank.png"));
  EXPECT_LT(drawn.different, 500);

  const ToolRun view = run_tool("view chain --links 5 --steps 10 --out " + dir + "/page");
  ASSERT_EQ(view.exit_code, 0) << view.err;
  std::string page = read_text(dir + "/page/index.html");
  page.replace(page.find("\"use strict\";"), 13, "\"use strict\"; no_such_function();");
  { std::ofstream(dir + "/page/broken.html") << page; }
  const BrowserRun broken =
      run_chromium(chromium, dir, "--dump-dom", "file://" + dir + "/page/broken.html");
  EXPECT_NE(body_attribute(broken.out, "data-state"), "ready");
  EXPECT_FALSE(console_lines(broken.log).empty());
}

}  // namespace
}  // namespace softstep::tool_test
