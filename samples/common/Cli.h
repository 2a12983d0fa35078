// The tools' command lines, parsed by CLI11: the help `--help` prints is generated from the
// options' own descriptions, and every tool answers a bad argument alike: a message naming the
// argument on stderr, a pointer to --help, exit status 2.
#pragma once

#include "engine/plugin/ParameterSet.h"
#include "engine/render/FrameInfo.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace tool {

/** A bad argument, or a bad combination found after parsing: the message on stderr, 2. */
inline int usageError(const std::string& tool, const std::string& message) {
    std::fprintf(stderr, "%s: %s\nRun %s --help for the options.\n", tool.c_str(), message.c_str(),
                 tool.c_str());
    return 2;
}

inline int usageError(const CLI::App& app, const std::string& message) {
    return usageError(app.get_name(), message);
}

/** Parses argv into `app`: nothing to go on with; 0 after --help (the help on stdout); 2 after a
 *  bad argument (the message on stderr). */
inline std::optional<int> parseArguments(CLI::App& app, int argc, char** argv) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        std::fputs(app.help().c_str(), stdout);
        return 0;
    } catch (const CLI::ExtrasError& error) { // "...not expected: ARGS": name them alike
        const std::string what = error.what();
        const std::string extras = what.substr(what.rfind(": ") + 2);
        return usageError(app,
                          (extras[0] == '-' ? "unknown option " : "unexpected argument ") + extras);
    } catch (const CLI::ParseError& error) {
        return usageError(app, error.what());
    }
    return std::nullopt;
}

/** `text` with every line longer than `width` broken between words. */
inline std::string wrap(const std::string& text, std::size_t width) {
    std::string wrapped;
    std::istringstream lines(text);
    for (std::string paragraph; std::getline(lines, paragraph);) {
        if (paragraph.size() <= width) {
            wrapped += paragraph + "\n";
            continue;
        }
        std::string line;
        std::istringstream words(paragraph);
        for (std::string word; words >> word;) {
            if (!line.empty() && line.size() + 1 + word.size() > width) {
                wrapped += line + "\n";
                line.clear();
            }
            line += (line.empty() ? "" : " ") + word;
        }
        wrapped += line + "\n";
    }
    return wrapped.empty() ? wrapped : wrapped.substr(0, wrapped.size() - 1);
}

/** CLI11's help with each option's description wrapped to 100 columns. */
class WrappingFormatter : public CLI::Formatter {
public:
    static constexpr std::size_t kColumn = 28, kWidth = 100;
    WrappingFormatter() { column_width(kColumn); }
    std::string make_option_desc(const CLI::Option* option) const override {
        return wrap(CLI::Formatter::make_option_desc(option), kWidth - kColumn);
    }
};

/** The app with the tools' common settings: `description` above the options, `footer`
 *  (the exit statuses) below them, help text wrapped to 100 columns. */
inline void configure(CLI::App& app, const std::string& description, const std::string& footer) {
    app.description(wrap(description, WrappingFormatter::kWidth) + "\n");
    app.footer(wrap(footer, WrappingFormatter::kWidth));
    app.formatter(std::make_shared<WrappingFormatter>());
}

/** One of `choices`, exactly (the help shows them in the option's own text). */
inline CLI::Validator oneOf(std::vector<std::string> choices) {
    CLI::Validator member = CLI::IsMember(std::move(choices));
    member.description("");
    return member;
}

/** A whole number in lo..hi (the help shows the bounds in the option's own text). */
inline CLI::Validator range(double lo, double hi) {
    return CLI::Range(lo, hi).description("");
}

/** "on" or "off" into a bool. */
inline CLI::Option* addOnOff(CLI::App& app, const std::string& name, bool& value,
                             const std::string& help) {
    return app
        .add_option_function<std::string>(
            name, [&value](const std::string& v) { value = v == "on"; }, help)
        ->check(oneOf({"on", "off"}))
        ->type_name("on|off");
}

/** The temporal history's own options into `t` (glass-capture's and glass-bench's): its weight,
 *  the jitter while anything moves, the rejection and clip, still frames' convergence; in
 *  `group` where one is named. */
inline void addHistoryOptions(CLI::App& app, render::TemporalSettings& t,
                              const std::string& group = {}) {
    std::vector<CLI::Option*> options{
        app.add_option("--history-weight", t.historyWeight,
                       "the history's weight while anything moves (default 0.7)")
            ->check(range(0.0, 0.99))
            ->type_name("0..0.99"),
        app.add_option("--moving-jitter", t.movingJitter,
                       "the jitter's extent while anything moves, a share of the pixel (still "
                       "frames take the whole pixel; default 0.5)")
            ->check(range(0.0, 1.0))
            ->type_name("0..1"),
        addOnOff(app, "--history-rejection", t.rejectHistory,
                 "off: keep every reprojected history unclipped (to show what the rejection and "
                 "clipping are for; default on)"),
        addOnOff(app, "--converge-still", t.convergeStill,
                 "off: frames at one time blend as moving ones do (the history weight, the "
                 "neighbourhood's clip) instead of averaging every frame (default on)")};
    if (!group.empty())
        for (CLI::Option* option : options)
            option->group(group);
}

/** WxH within `lo`..`limit` into `size` (x, y). */
template <class Size>
CLI::Option* addSize(CLI::App& app, const std::string& name, Size& size, int lo, int limit,
                     const std::string& help) {
    return app
        .add_option_function<std::string>(
            name,
            [&size, name, lo, limit](const std::string& v) {
                int w = 0, h = 0;
                char extra = 0;
                if (std::sscanf(v.c_str(), "%dx%d%c", &w, &h, &extra) != 2 || w < lo || h < lo ||
                    w > limit || h > limit)
                    throw CLI::ValidationError(name, "needs WxH within " + std::to_string(lo) +
                                                         ".." + std::to_string(limit) + ", got '" +
                                                         v + "'");
                size.x = w;
                size.y = h;
            },
            help)
        ->type_name("WxH");
}

/** A comma-separated list into `items` (replacing its defaults), each item converted by `item`
 *  (nothing: a bad one, which the option's error names, saying what `expected` is). */
template <class T>
CLI::Option* addList(CLI::App& app, const std::string& name, std::vector<T>& items,
                     std::function<std::optional<T>(const std::string&)> item,
                     const std::string& expected, const std::string& help) {
    return app.add_option_function<std::string>(
        name,
        [&items, name, item, expected](const std::string& v) {
            items.clear();
            std::stringstream in(v);
            for (std::string text; std::getline(in, text, ',');) {
                const std::optional<T> converted = item(text);
                if (!converted)
                    throw CLI::ValidationError(name, "needs " + expected + ", got '" + text + "'");
                items.push_back(*converted);
            }
        },
        help);
}

/** A finite number, as the options that take one read it. */
inline bool parseNumber(const std::string& s, double& out) {
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return !s.empty() && *end == '\0' && std::isfinite(out);
}

/** One option per parameter of `parameters` (--NAME VALUE, its help and choices from the
 *  parameter's declaration, checked as ParameterSet::set checks it), each given one appended to
 *  `given` as (name, value), in `group`; a value `intercept` takes (returns true for) is the
 *  tool's own and goes neither through the check nor into `given`. */
inline void
addParameterOptions(CLI::App& app, const plugin::ParameterSet& parameters,
                    std::vector<std::pair<std::string, std::string>>& given,
                    const std::string& group,
                    std::function<bool(const std::string&, const std::string&)> intercept = {}) {
    for (const plugin::Parameter& p : parameters.declarations()) {
        std::ostringstream bounds;
        bounds << p.min << ".." << p.max;
        std::string type = bounds.str();
        if (!p.choices.empty()) {
            type.clear();
            for (const std::string& choice : p.choices)
                type += (type.empty() ? "" : "|") + choice;
        } else if (p.type == plugin::Parameter::Type::Color) {
            type = "R,G,B";
        } else if (p.type == plugin::Parameter::Type::Bool) {
            type = "on|off";
        }
        std::ostringstream fallback;
        if (!p.choices.empty())
            fallback << p.choices[std::size_t(p.defaultValue)];
        else if (p.type == plugin::Parameter::Type::Bool)
            fallback << (p.defaultValue != 0.0 ? "on" : "off");
        else if (p.type == plugin::Parameter::Type::Color)
            fallback << p.defaultValue << "," << p.defaultValue << "," << p.defaultValue;
        else
            fallback << p.defaultValue;
        app.add_option_function<std::string>(
               "--" + p.name,
               [&given, &parameters, intercept, name = p.name](const std::string& v) {
                   if (intercept && intercept(name, v))
                       return;
                   plugin::ParameterSet check = parameters;
                   if (auto status = check.set(name, v); !status)
                       throw CLI::ValidationError("--" + name, status.error().message);
                   given.emplace_back(name, v);
               },
               p.help + " (default " + fallback.str() + ")")
            ->type_name(type)
            ->group(group);
    }
}

} // namespace tool
