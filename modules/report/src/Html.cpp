#include <mrloc/common/Error.h>
#include <mrloc/report/Html.h>

#include <cstdio>

namespace mrloc::report {

/** The one place that writes markup: an element around nodes that are already safe. */
struct HtmlWriter {
    static Html markup(std::string m) {
        Html h;
        h.markup_ = std::move(m);
        return h;
    }
    static Html element(const char* tag, const Html& content) {
        return markup(std::string("<") + tag + ">" + content.markup() + "</" + tag + ">");
    }
    static Html line(const char* tag, const Html& content) {
        return markup(element(tag, content).markup() + "\n");
    }
};

namespace {

/** & < > as entities, and the quotes too where the text goes into a quoted attribute. */
std::string escaped(const std::string& text, bool attribute) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        if (!attribute && (c == '\'' || c == '"')) {
            out += c;  // inert in an element's content
            continue;
        }
        switch (c) {
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '&':
                out += "&amp;";
                break;
            case '\'':
                out += "&#39;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

}  // namespace

std::string escapeHtml(const std::string& text) { return escaped(text, true); }

Html::Html(const std::string& text) : markup_(escaped(text, false)) {}
Html::Html(const char* text) : markup_(escaped(text ? text : "", false)) {}

Html& Html::operator+=(const Html& more) {
    markup_ += more.markup_;
    return *this;
}

Html operator+(Html a, const Html& b) { return a += b; }

Html heading(int level, const Html& content) {
    static const char* tags[] = {"h1", "h2", "h3"};
    if (level < 1 || level > 3) throw Error("report: heading level " + std::to_string(level));
    return HtmlWriter::line(tags[level - 1], content);
}

Html paragraph(const Html& content) { return HtmlWriter::line("p", content); }
Html bold(const Html& content) { return HtmlWriter::element("b", content); }
Html emphasis(const Html& content) { return HtmlWriter::element("em", content); }
Html code(const Html& content) { return HtmlWriter::element("code", content); }

namespace {

std::string encodedTarget(const std::string& target) {
    std::string out;
    for (unsigned char c : target) {
        if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
            c == '-' || c == '.' || c == '_' || c == '~' || c == '/') {
            out += char(c);
        } else {
            char hex[4];
            std::snprintf(hex, sizeof hex, "%%%02X", c);
            out += hex;
        }
    }
    return out;
}

}  // namespace

// The attributes below hold only encodedTarget's characters (no quote, no ':') and
// escapeHtml's text; `content` is already a node.
Html link(const std::string& target, const Html& content) {
    return HtmlWriter::markup("<a href='" + encodedTarget(target) + "'>" + content.markup() +
                              "</a>");
}

Html bulletList(const std::vector<Html>& items) {
    std::string m = "<ul>\n";
    for (const auto& item : items) m += HtmlWriter::line("li", item).markup();
    return HtmlWriter::markup(m + "</ul>\n");
}

Html Figure::html() const {
    const std::string words = escapeHtml(caption);
    return HtmlWriter::markup("<figure><img src='" + encodedTarget(file) + "' alt='" + words +
                              "'><figcaption>" + words + "</figcaption></figure>\n");
}

Table::Table(std::vector<Html> head) : head_(std::move(head)) {}

Table& Table::row(std::vector<Html> cells) {
    rows_.push_back({false, std::move(cells)});
    return *this;
}

Table& Table::headedRow(const Html& head, std::vector<Html> cells) {
    cells.insert(cells.begin(), head);
    rows_.push_back({true, std::move(cells)});
    return *this;
}

Html Table::html() const {
    Html t = HtmlWriter::markup("<table>\n");
    const auto tr = [&](const std::vector<Html>& cells, bool firstIsHead, bool allHead) {
        Html r;
        for (size_t i = 0; i < cells.size(); ++i)
            r += HtmlWriter::element(allHead || (firstIsHead && i == 0) ? "th" : "td", cells[i]);
        t += HtmlWriter::line("tr", r);
    };
    if (!head_.empty()) tr(head_, false, true);
    for (const auto& r : rows_) tr(r.cells, r.headed, false);
    return t + HtmlWriter::markup("</table>\n");
}

std::string htmlPage(const std::string& title, const Html& body) {
    return "<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>" + escaped(title, false) +
           "</title>\n<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto}"
           "table{border-collapse:collapse;margin:1em 0}th,td{border:1px solid #ccc;"
           "padding:3px 8px;text-align:left;vertical-align:top}img{max-width:100%;border:1px solid "
           "#ddd}figure{margin:1em 0 1.5em}figcaption{color:#444;font-style:italic;margin-top:.3em}"
           "</style>"
           "</head><body>\n" +
           body.markup() + "</body></html>\n";
}

}  // namespace mrloc::report
