#pragma once
// Each key of an INI section declared once: name, member, bounds, unit, one line of doc.
//
// MRPT's MRPT_LOAD_CONFIG_VAR reads a key into a member, and saveToConfigFile writes it back
// by hand: the name is spelt twice and the bounds live nowhere. A KeyTable holds, per key,
// what loading (strict parsing and range checks through IniSection, so an unknown key is
// refused with "did you mean"), effective.ini (saveToConfigFile), --set (which is loading) and
// the key tables of doc/ini.md (`mrloc keys`, checked by a test) all use. The default is the
// struct's member initializer, written once; a key absent leaves the member as it is.
//
//   static const auto& table = common::KeyTable<OmniOptions>("omnivision")
//       .real("t_b", MRLOC_KEY_FIELD(tb), {0, 1e6}, "s", "the pairs stop at")
//       .flag("refine", MRLOC_KEY_FIELD(refine), "refine the layout by least squares");
//
// What ties several keys together (t_e after t_b) stays in the loader, after table.load().
#include <mrloc/common/IniSection.h>
#include <mrloc/common/Seeds.h>
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>

#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

/** The member a key sets, as an accessor both loading (O&) and saving (const O&) use. */
#define MRLOC_KEY_FIELD(member) \
    [](auto& o) -> auto& { return o.member; }

namespace mrloc::common {

/** One key as doc/ini.md shows it. */
struct KeyDoc {
    std::string name;         ///< "t_b"; a family: "beacon_<id>"
    std::string defaultText;  ///< "10", "(none)", "(required)"
    std::string unit;         ///< "s", "deg", "" (none)
    std::string range;        ///< "0 .. 1e+06", "proposed, conventional", "" (any)
    std::string doc;          ///< one line
};

/** A table's keys as the docs show them. */
struct SectionKeys {
    std::string section;  ///< "omnivision", "robot.<name>"
    std::vector<KeyDoc> keys;
};

/** "1.7e+09" as an INI would say it; integers without a point. */
std::string keyNumberText(double x);
/** A real's value as effective.ini writes it: keyNumberText when that reads back (through
 *  `toMember`) as the very value the member holds, else every digit it takes (MRPT's own
 *  write of a double keeps 6 decimals: 1e-7 became 0, and a run from effective.ini was not
 *  the run). */
std::string keyValueText(double member, double (*toMember)(double) = nullptr,
                         double (*toIni)(double) = nullptr);
/** A pose's angle kept in radians, written in degrees to 12 significant digits (a pose's
 *  angle reads back through its class's own arithmetic, never bit for bit). */
std::string keyDegreesText(double radians);

/** "0 .. 10", "at least 0", "at most 5", or "" when unbounded. */
std::string keyRangeText(double lo, double hi, const std::string& loKey = "",
                         const std::string& hiKey = "");
/** The Markdown table doc/ini.md holds for a section (without a heading). */
std::string keysMarkdown(const SectionKeys& keys);

/** A bound on a key: a number, or the value of another key of the same table read before
 *  this one (pair_gap is at least erp_baseline). */
struct KeyBound {
    double value;
    std::string key;
    KeyBound(double v) : value(v) {}               // NOLINT: a number is a bound
    KeyBound(int v) : value(v) {}                  // NOLINT: (a literal 0 is also a null pointer)
    KeyBound(const char* k) : value(0), key(k) {}  // NOLINT: so is a key's name
};
struct KeyRange {
    KeyBound lo = -IniSection::kInf;
    KeyBound hi = IniSection::kInf;
};

/** The values a list key takes: each from lo to hi (and whole, when `whole` or the member's
 *  element type is integral), at least `least` and at most `most` of them (each value is
 *  work: a column, a sweep, a room of trials). */
struct KeyList {
    double lo, hi;
    size_t most;
    size_t least = 0;
    bool whole = false;
};
/** A list as effective.ini and the docs write it: "3 4 5", each value as keyValueText writes
 *  it (every digit it holds): list keys, and poses, boxes and waypoints. */
std::string keyListText(const std::vector<double>& values);
/** Reads a list key, refusing too many or too few values and any out of range (or not whole,
 *  when `whole`): one check for every list key. */
std::vector<double> readKeyList(IniSection& s, const std::string& name, std::vector<double> def,
                                const KeyList& list, bool whole, const std::string& unit);

template <class Options>
class KeyTable {
 public:
    explicit KeyTable(std::string section) : section_(std::move(section)) {}

    const std::string& section() const { return section_; }

    /** A real number; `unit` is the INI's (the member holds the same). */
    template <class Field>
    KeyTable& real(const std::string& name, Field field, KeyRange range, std::string unit,
                   std::string doc) {
        const auto same = [](double x) { return x; };
        return number(name, field, range, std::move(unit), std::move(doc), same, same);
    }
    /** An angle: degrees in the INI, radians in the member. */
    template <class Field>
    KeyTable& degrees(const std::string& name, Field field, KeyRange range, std::string doc) {
        // mrpt::DEG2RAD and RAD2DEG themselves ((x * pi) / 180, not x * (pi / 180)): values
        // round as they did before the table
        return number(
            name, field, range, "deg", std::move(doc), [](double x) { return mrpt::DEG2RAD(x); },
            [](double x) { return mrpt::RAD2DEG(x); });
    }
    /** A whole number into any integral member. */
    template <class Field>
    KeyTable& integer(const std::string& name, Field field, long lo, long hi, std::string unit,
                      std::string doc) {
        Key k(KeyDoc{name, "", std::move(unit), keyRangeText(double(lo), double(hi)),
                     std::move(doc)});
        k.load = [=](IniSection& s, Options& o) {
            auto& m = field(o);
            m = static_cast<std::remove_reference_t<decltype(m)>>(s.integer(name, long(m), lo, hi));
        };
        k.save = [=](const Options& o, mrpt::config::CConfigFileBase& t, const std::string& sec) {
            t.write(sec, name, field(o));
        };
        k.defaultText = [=](const Options& o) { return std::to_string(field(o)); };
        return add(std::move(k));
    }
    template <class Field>
    KeyTable& flag(const std::string& name, Field field, std::string doc) {
        Key k(KeyDoc{name, "", "", "true, false", std::move(doc)});
        k.load = [=](IniSection& s, Options& o) { field(o) = s.flag(name, field(o)); };
        k.save = [=](const Options& o, mrpt::config::CConfigFileBase& t, const std::string& sec) {
            t.write(sec, name, bool(field(o)));
        };
        k.defaultText = [=](const Options& o) { return std::string(field(o) ? "true" : "false"); };
        return add(std::move(k));
    }
    /** Free text; an empty default reads "(none)" in the docs. */
    template <class Field>
    KeyTable& text(const std::string& name, Field field, std::string doc) {
        Key k(KeyDoc{name, "", "", "", std::move(doc)});
        k.load = [=](IniSection& s, Options& o) { field(o) = s.text(name, field(o)); };
        k.save = [=](const Options& o, mrpt::config::CConfigFileBase& t, const std::string& sec) {
            t.write(sec, name, std::string(field(o)));
        };
        k.defaultText = [=](const Options& o) { return std::string(field(o)); };
        return add(std::move(k));
    }
    /** One of fixed words, each standing for a value of the member (a bool, an enum, a
     *  string). */
    template <class Field, class T>
    KeyTable& choice(const std::string& name, Field field,
                     std::vector<std::pair<std::string, T>> words, std::string doc) {
        std::string list;
        for (const auto& w : words) list += (list.empty() ? "" : ", ") + w.first;
        Key k(KeyDoc{name, "", "", list, std::move(doc)});
        auto wordOf = [=](const Options& o) {
            for (const auto& w : words)
                if (w.second == field(o)) return w.first;
            return words.front().first;
        };
        k.load = [=](IniSection& s, Options& o) {
            std::vector<std::string> names;
            for (const auto& w : words) names.push_back(w.first);
            const std::string word = s.choice(name, wordOf(o), names);
            for (const auto& w : words)
                if (w.first == word) field(o) = w.second;
        };
        k.save = [=](const Options& o, mrpt::config::CConfigFileBase& t, const std::string& sec) {
            t.write(sec, name, wordOf(o));
        };
        k.defaultText = wordOf;
        return add(std::move(k));
    }
    /** A string member that takes one of these words. */
    template <class Field>
    KeyTable& choice(const std::string& name, Field field, const std::vector<std::string>& words,
                     std::string doc) {
        std::vector<std::pair<std::string, std::string>> pairs;
        for (const auto& w : words) pairs.push_back({w, w});
        return choice(name, field, pairs, std::move(doc));
    }
    /** A list of numbers into a std::vector of reals or of integers. An empty list is
     *  written empty. */
    template <class Field>
    KeyTable& numbers(const std::string& name, Field field, KeyList list, std::string unit,
                      std::string doc) {
        using Element =
            typename std::decay_t<decltype(field(std::declval<Options&>()))>::value_type;
        const bool whole = list.whole || std::is_integral_v<Element>;
        std::string range =
            keyRangeText(list.lo, list.hi) + ", at most " + std::to_string(list.most) + " values";
        if (list.least > 0) range += " (at least " + std::to_string(list.least) + ")";
        if (whole) range += ", whole numbers";
        Key k(KeyDoc{name, "", unit, range, std::move(doc)});
        auto asReals = [=](const Options& o) {
            return std::vector<double>(field(o).begin(), field(o).end());
        };
        k.load = [=](IniSection& s, Options& o) {
            const auto v = readKeyList(s, name, asReals(o), list, whole, unit);
            field(o).assign(v.begin(), v.end());  // whole numbers: checked before the cast
        };
        k.save = [=](const Options& o, mrpt::config::CConfigFileBase& t, const std::string& sec) {
            t.write(sec, name, keyListText(asReals(o)));
        };
        k.defaultText = [=](const Options& o) { return keyListText(asReals(o)); };
        return add(std::move(k));
    }
    /** A key read and written by the method's own code (a list of pairs, a pose). `save`
     *  returns nothing when the key is left out of effective.ini (an override not given);
     *  `defaultText`, when given, is what the docs show instead of save's text. */
    KeyTable& custom(const std::string& name, std::string unit, std::string range, std::string doc,
                     std::function<void(IniSection&, Options&)> load,
                     std::function<std::optional<std::string>(const Options&)> save,
                     std::optional<std::string> defaultText = std::nullopt) {
        Key k(KeyDoc{name, "", std::move(unit), std::move(range), std::move(doc)});
        k.load = std::move(load);
        k.save = [=](const Options& o, mrpt::config::CConfigFileBase& t, const std::string& sec) {
            if (const auto v = save(o)) t.write(sec, name, *v);
        };
        k.defaultText = [=](const Options& o) {
            if (defaultText) return *defaultText;
            const auto v = save(o);
            return v ? *v : std::string("(none)");
        };
        return add(std::move(k));
    }
    /** A sub-seed override (common/Seeds.h): absent, drawn from the run's seed for `purpose`
     *  (or the run's seed itself when `purpose` is empty); written back only when given. */
    template <class Field>
    KeyTable& subSeed(const std::string& name, Field field, std::string purpose, std::string doc) {
        Key k(KeyDoc{name, "", "", keyRangeText(0, double(kMaxSeed)), std::move(doc)});
        k.load = [=](IniSection& s, Options& o) {
            const auto run = runSeed(s.config());
            field(o) = purpose.empty() ? common::subSeed(s, name, run)
                                       : common::subSeed(s, name, run, purpose);
        };
        k.save = [=](const Options& o, mrpt::config::CConfigFileBase& t, const std::string& sec) {
            if (field(o).given) t.write(sec, name, std::to_string(field(o).value));
        };
        k.defaultText = [=](const Options&) {
            return std::string(purpose.empty() ? "(the run's seed)"
                                               : "(drawn from the run's seed)");
        };
        return add(std::move(k));
    }
    /** A family of keys `<prefix><name>` (`sonar_<name>`) that `load` reads itself (allowing
     *  the prefix) and `save` writes, one key per member. */
    KeyTable& family(
        const std::string& shown, std::string unit, std::string range, std::string doc,
        std::function<void(IniSection&, Options&)> load,
        std::function<void(const Options&, mrpt::config::CConfigFileBase&, const std::string&)>
            save,
        std::string defaultText = "(none)") {
        Key k(KeyDoc{shown, std::move(defaultText), std::move(unit), std::move(range),
                     std::move(doc)});
        k.load = std::move(load);
        k.save = std::move(save);
        return add(std::move(k));
    }
    /** The key declared last is written into effective.ini only when `keep` holds (a key
     *  another one makes moot: `start_site` beside a `start`). */
    KeyTable& savedOnlyIf(std::function<bool(const Options&)> keep) {
        keys_.back().save = onlyIf(std::move(keys_.back().save), std::move(keep));
        return *this;
    }
    /** Every key declared from here on is written only when `keep` holds (a group that one
     *  choice makes moot: polymap's scan keys beside `localizer = exact`). */
    KeyTable& savedFromHereOnlyIf(std::function<bool(const Options&)> keep) {
        groupKeep_ = std::move(keep);
        return *this;
    }

    /** Reads every key in declared order into `o` (absent: left as it is). */
    void load(IniSection& s, Options& o) const {
        for (const auto& k : keys_)
            if (k.load) k.load(s, o);
    }
    /** Writes every key in declared order (effective.ini). */
    void save(const Options& o, mrpt::config::CConfigFileBase& t, const std::string& sec) const {
        for (const auto& k : keys_)
            if (k.save) k.save(o, t, sec);
    }
    /** The keys as the docs show them, defaults from a default-constructed Options. */
    SectionKeys docs(const Options& defaults = Options{}) const {
        SectionKeys out{section_, {}};
        for (const auto& k : keys_) {
            KeyDoc d = k.doc;
            if (k.defaultText) d.defaultText = k.defaultText(defaults);
            if (d.defaultText.empty()) d.defaultText = "(none)";
            out.keys.push_back(std::move(d));
        }
        return out;
    }

 private:
    struct Key {
        explicit Key(KeyDoc d) : doc(std::move(d)) {}
        KeyDoc doc;
        std::function<void(IniSection&, Options&)> load;
        std::function<void(const Options&, mrpt::config::CConfigFileBase&, const std::string&)>
            save;
        std::function<std::string(const Options&)> defaultText;
        std::function<double(const Options&)> inIniUnit;  ///< a real's value, for bounds
    };

    using Saver =
        std::function<void(const Options&, mrpt::config::CConfigFileBase&, const std::string&)>;

    static Saver onlyIf(Saver save, std::function<bool(const Options&)> keep) {
        if (!save) return save;
        return [save = std::move(save), keep = std::move(keep)](
                   const Options& o, mrpt::config::CConfigFileBase& t, const std::string& sec) {
            if (keep(o)) save(o, t, sec);
        };
    }

    KeyTable& add(Key k) {
        if (groupKeep_) k.save = onlyIf(std::move(k.save), groupKeep_);
        keys_.push_back(std::move(k));
        return *this;
    }

    /** A bound: a number, or the value of a real key declared before, in the INI's unit (the
     *  getter is copied: the table is built as a temporary and then copied). */
    std::function<double(const Options&)> boundOf(const KeyBound& b) const {
        if (b.key.empty()) return [v = b.value](const Options&) { return v; };
        for (const auto& k : keys_)
            if (k.doc.name == b.key && k.inIniUnit) return k.inIniUnit;
        throw std::logic_error("key table [" + section_ + "]: bound '" + b.key +
                               "' is not a real key declared before");
    }

    template <class Field>
    KeyTable& number(const std::string& name, Field field, KeyRange range, std::string unit,
                     std::string doc, double (*toMember)(double), double (*toIni)(double)) {
        Key k(KeyDoc{name, "", std::move(unit),
                     keyRangeText(range.lo.value, range.hi.value, range.lo.key, range.hi.key),
                     std::move(doc)});
        k.inIniUnit = [=](const Options& o) { return toIni(double(field(o))); };
        k.load = [=, lo = boundOf(range.lo), hi = boundOf(range.hi)](IniSection& s, Options& o) {
            if (s.has(name))
                field(o) = toMember(s.real(name, 0.0, lo(o), hi(o)));
            else
                (void)s.real(name, 0.0);  // asked for: finish() accepts it
        };
        k.save = [=](const Options& o, mrpt::config::CConfigFileBase& t, const std::string& sec) {
            t.write(sec, name, keyValueText(double(field(o)), toMember, toIni));
        };
        k.defaultText = [=](const Options& o) { return keyNumberText(toIni(double(field(o)))); };
        return add(std::move(k));
    }

    std::string section_;
    std::vector<Key> keys_;
    std::function<bool(const Options&)> groupKeep_;  ///< savedFromHereOnlyIf's, if any
};

}  // namespace mrloc::common
