// The report's HTML builder (report/Html.h): text is escaped where it becomes a node, links
// and pictures cannot carry a scheme or leave their attribute, tables are well formed, and a
// run folder whose metrics.json names a path for a robot is refused before anything is read.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/report/Html.h>
#include <mrloc/report/Report.h>

#include <filesystem>
#include <fstream>

using namespace mrloc;
using report::Html;

TEST(Html, TextIsEscapedWhereItBecomesANode) {
    EXPECT_EQ(Html("<script>alert('x') & \"y\"</script>").markup(),
              "&lt;script&gt;alert('x') &amp; \"y\"&lt;/script&gt;");
    EXPECT_EQ(report::escapeHtml("a'b\"c<&>"), "a&#39;b&quot;c&lt;&amp;&gt;");
    // joined text stays text, however it was built
    const std::string name = "r1'><img src=x onerror=alert(1)>";
    const Html joined = "robot " + report::bold(name) + " " + name;
    EXPECT_EQ(joined.markup().find('<', joined.markup().find("</b>") + 1), std::string::npos);
    EXPECT_EQ(joined.markup(),
              "robot <b>r1'&gt;&lt;img src=x onerror=alert(1)&gt;</b> "
              "r1'&gt;&lt;img src=x onerror=alert(1)&gt;");
    EXPECT_EQ(report::paragraph(report::code("a<b") + report::emphasis("c&d")).markup(),
              "<p><code>a&lt;b</code><em>c&amp;d</em></p>\n");
    EXPECT_EQ(report::heading(2, "x > y").markup(), "<h2>x &gt; y</h2>\n");
    EXPECT_THROW(report::heading(4, "too deep"), Error);
    EXPECT_TRUE(Html().empty());
    EXPECT_TRUE(Html(std::string()).empty());
}

TEST(Html, LinksAndFiguresHoldNoSchemeAndStayInTheirAttribute) {
    EXPECT_EQ(report::link("effective.ini", "effective.ini").markup(),
              "<a href='effective.ini'>effective.ini</a>");
    EXPECT_EQ(report::link("javascript:alert(1)", "x").markup(),
              "<a href='javascript%3Aalert%281%29'>x</a>");
    EXPECT_EQ((report::Figure{"polymap.r1.png", "map, V and 'hypotheses'"}).html().markup(),
              "<figure><img src='polymap.r1.png' alt='map, V and &#39;hypotheses&#39;'><figcaption>"
              "map, V and &#39;hypotheses&#39;</figcaption></figure>\n");
    const auto img = (report::Figure{"a' onerror='alert(1).png", "x"}).html().markup();
    EXPECT_EQ(img,
              "<figure><img src='a%27%20onerror%3D%27alert%281%29.png' alt='x'><figcaption>x"
              "</figcaption></figure>\n");
    EXPECT_EQ((report::Figure{"\xc3\xa9t\xc3\xa9.png", ""}).html().markup(),
              "<figure><img src='%C3%A9t%C3%A9.png' alt=''><figcaption></figcaption></figure>\n");
}

TEST(Html, TablesAreWellFormed) {
    report::Table t({"robot", "RMSE (m)"});
    t.row({"<r1>", "0.1"}).headedRow("mean", {"0.2"});
    EXPECT_EQ(t.rows(), 2u);
    EXPECT_EQ(t.html().markup(),
              "<table>\n<tr><th>robot</th><th>RMSE (m)</th></tr>\n"
              "<tr><td>&lt;r1&gt;</td><td>0.1</td></tr>\n"
              "<tr><th>mean</th><td>0.2</td></tr>\n</table>\n");
    EXPECT_EQ(report::bulletList({"a", "<b>"}).markup(),
              "<ul>\n<li>a</li>\n<li>&lt;b&gt;</li>\n</ul>\n");
    const std::string page = report::htmlPage("mrloc report: </title><script>", t.html());
    EXPECT_NE(page.find("<title>mrloc report: &lt;/title&gt;&lt;script&gt;</title>"),
              std::string::npos);
    EXPECT_EQ(page.find("<script>"), std::string::npos);
}

TEST(Html, MetricsCellsReadAsText) {
    EXPECT_EQ(report::cellText(nullptr), "none");
    EXPECT_EQ(report::cellText(true), "yes");
    EXPECT_EQ(report::cellText(0.123456), "0.1235");
    EXPECT_EQ(report::cellText(nlohmann::json::array({1, 2.5})), "1, 2.5");
    EXPECT_EQ(
        report::metricsTable({{"rmse_m", 0.5}, {"name", "<x>"}, {"robots", {{"r1", 1}}}}).markup(),
        "<table>\n<tr><th>name</th><td>&lt;x&gt;</td></tr>\n"
        "<tr><th>RMSE (m)</th><td>0.5</td></tr>\n</table>\n");
}

TEST(Html, ARunFolderWhoseRobotIsAPathIsRefused) {
    namespace fs = std::filesystem;
    const std::string dir = testing::TempDir() + "/html_robot_path";
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir + "/metrics.json")
        << R"({"method": "polymap", "robots": {"../../outside": {"estimates": 1}}})";
    try {
        report::makeReport(dir, {});
        FAIL() << "a robot named ../../outside was taken";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("../../outside"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("metrics.json"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir + "/report.html"));
}
