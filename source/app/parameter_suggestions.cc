#include <deal.II/base/exceptions.h>

#include <deal.II/base/utilities.h>

#include <cycloid/app/parameter_suggestions.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <numeric>
#include <regex>
#include <sstream>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

namespace cycloid
{
  namespace app
  {
    namespace
    {
      std::string
      lower(std::string s)
      {
        std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) {
          return std::tolower(c);
        });
        return s;
      }



      /** Edit distance with adjacent transpositions (optimal string
       * alignment): "widht" is one typo away from "width", not two. */
      std::size_t
      edit_distance(const std::string &a, const std::string &b)
      {
        std::vector<std::vector<std::size_t>> d(
          a.size() + 1, std::vector<std::size_t>(b.size() + 1));
        for (std::size_t i = 0; i <= a.size(); ++i)
          d[i][0] = i;
        for (std::size_t j = 0; j <= b.size(); ++j)
          d[0][j] = j;
        for (std::size_t i = 1; i <= a.size(); ++i)
          for (std::size_t j = 1; j <= b.size(); ++j)
            {
              const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
              d[i][j]                = std::min(
                {d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
              if (i > 1 && j > 1 && a[i - 1] == b[j - 2] &&
                  a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
            }
        return d[a.size()][b.size()];
      }



      /** "'a'", "'a' or 'b'", "'a', 'b' or 'c'". */
      std::string
      quoted_list(const std::vector<std::string> &names)
      {
        std::string s;
        for (std::size_t i = 0; i < names.size(); ++i)
          s += (i == 0                ? "" :
                i + 1 == names.size() ? " or " :
                                        ", ") +
               ("'" + names[i] + "'");
        return s;
      }



      /** The values of a "[Selection a|b|c ]" pattern; empty for any other
       * pattern. */
      std::vector<std::string>
      selection_values(const std::string &pattern)
      {
        const std::string head = "[Selection ";
        if (pattern.compare(0, head.size(), head) != 0 || pattern.back() != ']')
          return {};
        const std::string list =
          pattern.substr(head.size(), pattern.size() - head.size() - 1);
        std::vector<std::string> values;
        for (const auto &v : dealii::Utilities::split_string_list(list, '|'))
          values.push_back(dealii::Utilities::trim(v));
        return values;
      }



      /** Whether @p line starts with the keyword @p word (deal.II accepts
       * it in lower or upper case) followed by a space; if so, remove it. */
      bool
      take_keyword(std::string &line, const std::string &word)
      {
        const std::string upper = [&word]() {
          std::string s = word;
          for (char &c : s)
            c = std::toupper(static_cast<unsigned char>(c));
          return s;
        }();
        for (const std::string &w : {word + " ", upper + " "})
          if (dealii::Utilities::match_at_string_start(line, w))
            {
              line = dealii::Utilities::trim(line.substr(w.size()));
              return true;
            }
        return false;
      }
    } // namespace



    DeclaredParameters::DeclaredParameters(const dealii::ParameterHandler &prm)
    {
      std::stringstream json;
      prm.print_parameters(json, dealii::ParameterHandler::JSON);
      boost::property_tree::ptree tree;
      boost::property_tree::read_json(json, tree);
      read_section(tree, top);
    }



    void
    DeclaredParameters::read_section(const boost::property_tree::ptree &tree,
                                     Section                           &section)
    {
      // deal.II prints an entry as an object with "value" and
      // "pattern_description"; every other object is a subsection.
      for (const auto &[name, node] : tree)
        if (node.get_child_optional("value") &&
            node.get_child_optional("pattern_description"))
          {
            section.entries.push_back(name);
            section.patterns.push_back(
              node.get<std::string>("pattern_description"));
          }
        else if (!node.empty())
          {
            section.names.push_back(name);
            section.children.emplace_back();
            read_section(node, section.children.back());
          }
    }



    std::vector<std::string>
    DeclaredParameters::closest(const std::string              &name,
                                const std::vector<std::string> &candidates,
                                const unsigned int              n_max)
    {
      const std::string key = lower(name);
      // A third of the length: two typos in "Geometry", three in "Tooth
      // width"; a short name like "Run" allows one.
      const std::size_t limit = std::max<std::size_t>(1, key.size() / 3);
      std::vector<std::pair<std::size_t, std::size_t>> scored; // (d, index)
      for (std::size_t i = 0; i < candidates.size(); ++i)
        {
          const std::string c = lower(candidates[i]);
          const std::size_t d = edit_distance(key, c);
          if (d <= limit ||
              (key.size() >= 4 && c.find(key) != std::string::npos))
            scored.emplace_back(d, i);
        }
      std::stable_sort(scored.begin(), scored.end());
      std::vector<std::string> result;
      for (std::size_t k = 0; k < scored.size() && k < n_max; ++k)
        result.push_back(candidates[scored[k].second]);
      return result;
    }



    std::vector<std::vector<std::string>>
    DeclaredParameters::entries() const
    {
      std::vector<std::vector<std::string>> result;
      const std::function<void(const Section &, std::vector<std::string> &)>
        walk = [&](const Section &section, std::vector<std::string> &path) {
          for (const std::string &entry : section.entries)
            {
              result.push_back(path);
              result.back().push_back(entry);
            }
          for (unsigned int i = 0; i < section.names.size(); ++i)
            {
              path.push_back(section.names[i]);
              walk(section.children[i], path);
              path.pop_back();
            }
        };
      std::vector<std::string> path;
      walk(top, path);
      return result;
    }



    const DeclaredParameters::Section *
    DeclaredParameters::find(const std::vector<std::string> &path) const
    {
      const Section *s = &top;
      for (const std::string &name : path)
        {
          const auto it = std::find(s->names.begin(), s->names.end(), name);
          if (it == s->names.end())
            return nullptr;
          s = &s->children[it - s->names.begin()];
        }
      return s;
    }



    std::string
    DeclaredParameters::where(const std::vector<std::string> &path)
    {
      if (path.empty())
        return "at the top level";
      std::string joined = path.front();
      for (std::size_t i = 1; i < path.size(); ++i)
        joined += "/" + path[i];
      return "in subsection '" + joined + "'";
    }



    std::vector<std::vector<std::string>>
    DeclaredParameters::places_of(const std::string &name,
                                  const bool         subsection) const
    {
      // Depth-first over the tree; a place is the path of the section that
      // declares the name, followed by its declared spelling.
      std::vector<std::vector<std::string>> places;
      std::vector<std::string>              path;
      const std::string                     key = lower(name);
      const auto visit = [&](const auto &self, const Section &s) -> void {
        for (const std::string &n : subsection ? s.names : s.entries)
          if (lower(n) == key)
            {
              places.push_back(path);
              places.back().push_back(n);
            }
        for (std::size_t i = 0; i < s.children.size(); ++i)
          {
            path.push_back(s.names[i]);
            self(self, s.children[i]);
            path.pop_back();
          }
      };
      visit(visit, top);
      return places;
    }



    std::string
    DeclaredParameters::explain_unknown(const std::string              &name,
                                        const std::vector<std::string> &path,
                                        const bool subsection) const
    {
      const char *kind = subsection ? "subsection" : "entry";
      std::string text =
        "there is no " + std::string(kind) + " '" + name + "' " + where(path);
      bool helped = false;
      for (auto place : places_of(name, subsection))
        {
          const std::string spelled = place.back();
          place.pop_back();
          if (place == path)
            continue; // the same name in another case: suggested below
          text += "; '" + spelled + "' is declared " + where(place);
          helped = true;
        }
      const Section *s = find(path);
      const auto     suggestions =
        s == nullptr ? std::vector<std::string>() :
                           closest(name, subsection ? s->names : s->entries);
      if (!suggestions.empty())
        text += (helped ? "; or did you mean " : "; did you mean ") +
                quoted_list(suggestions) + "?";
      else if (!helped)
        text += " (cycloid-contact --print-parameters lists every declared "
                "name)";
      return text;
    }



    std::string
    DeclaredParameters::explain_value(
      const std::string              &name,
      const std::string              &value,
      const std::vector<std::string> &path) const
    {
      const Section &s = *find(path);
      const auto     i =
        std::find(s.entries.begin(), s.entries.end(), name) - s.entries.begin();
      const std::string &pattern = s.patterns[i];
      // deal.II's factory knows its own patterns only (and throws for
      // others, such as parameters::OrAuto): then the value is reported
      // against the description.
      std::unique_ptr<dealii::Patterns::PatternBase> check;
      try
        {
          check = dealii::Patterns::pattern_factory(pattern);
        }
      catch (const dealii::ExceptionBase &)
        {}
      if (check != nullptr && check->match(value))
        return "";
      const auto        values = selection_values(pattern);
      const std::string entry  = "'" + name + "' " + where(path);
      if (values.empty())
        return "the value '" + value + "' of " + entry +
               " does not match the pattern " + pattern;
      std::string text =
        "'" + value + "' is not a valid value of " + entry +
        "; the values are " +
        std::accumulate(std::next(values.begin()),
                        values.end(),
                        values.front(),
                        [](const std::string &a, const std::string &b) {
                          return a + ", " + b;
                        });
      const auto suggestions = closest(value, values);
      if (!suggestions.empty())
        text += "; did you mean " + quoted_list(suggestions) + "?";
      return text;
    }



    std::string
    DeclaredParameters::explain_line(const std::string &filename,
                                     const unsigned int line_number) const
    {
      std::vector<std::string> path;
      for (const auto &[number, text] : logical_lines(filename))
        {
          std::string line = text;
          const bool  here = number == line_number;
          if (take_keyword(line, "subsection"))
            {
              const Section *s = find(path);
              if (here)
                return s != nullptr &&
                           std::find(s->names.begin(), s->names.end(), line) ==
                             s->names.end() ?
                         explain_unknown(line, path, true) :
                         "";
              path.push_back(line);
            }
          else if (line == "end" || line == "END")
            {
              if (!path.empty())
                path.pop_back();
            }
          else if (here && take_keyword(line, "set") &&
                   line.find('=') != std::string::npos)
            {
              const std::string name =
                dealii::Utilities::trim(line.substr(0, line.find('=')));
              const std::string value =
                dealii::Utilities::trim(line.substr(line.find('=') + 1));
              const Section *s = find(path);
              if (s == nullptr)
                return "";
              if (std::find(s->entries.begin(), s->entries.end(), name) ==
                  s->entries.end())
                return explain_unknown(name, path, false);
              return explain_value(name, value, path);
            }
          if (number >= line_number)
            return "";
        }
      return "";
    }



    std::vector<std::pair<unsigned int, std::string>>
    logical_lines(const std::string &filename)
    {
      // The same line handling as ParameterHandler::parse_input(): trimmed
      // lines, a trailing '\' continues on the next line, whose logical
      // line number is that of its first physical line.
      std::ifstream                                     in(filename);
      std::vector<std::pair<unsigned int, std::string>> lines;
      std::string                                       physical, logical;
      unsigned int                                      n = 0, logical_n = 0;
      while (std::getline(in, physical))
        {
          ++n;
          if (logical.empty())
            logical_n = n;
          physical = dealii::Utilities::trim(physical);
          if (!physical.empty() && physical.back() == '\\')
            {
              logical += physical.substr(0, physical.size() - 1);
              continue;
            }
          std::string line = logical + physical;
          logical.clear();
          if (line.find('#') != std::string::npos)
            line.erase(line.find('#'));
          std::replace(line.begin(), line.end(), '\t', ' ');
          lines.emplace_back(logical_n, dealii::Utilities::trim(line));
        }
      return lines;
    }



    void
    record_entries_set(dealii::ParameterHandler           &prm,
                       std::map<std::string, std::string> &set)
    {
      for (const std::vector<std::string> &path :
           DeclaredParameters(prm).entries())
        {
          std::string key;
          for (unsigned int i = 0; i + 1 < path.size(); ++i)
            {
              prm.enter_subsection(path[i]);
              key += path[i] + "/";
            }
          key += path.back();
          prm.add_action(path.back(), [&set, key](const std::string &value) {
            set[key] = value;
          });
          for (unsigned int i = 0; i + 1 < path.size(); ++i)
            prm.leave_subsection();
        }
      set.clear();
    }



    void
    parse_input_explained(dealii::ParameterHandler &prm,
                          const std::string        &filename)
    {
      try
        {
          prm.parse_input(filename);
        }
      catch (const dealii::ExceptionBase &e)
        {
          // deal.II's parse errors start with "Line <n> of file <name>"
          // (ExcNoSubsection omits the closing '>'); explain that line if it
          // is in this file, not in an included one.
          std::ostringstream info;
          e.print_info(info);
          const std::string text = info.str();
          std::smatch       m;
          if (!std::regex_search(text,
                                 m,
                                 std::regex("Line <([0-9]+)> of file <")))
            throw;
          const std::string after = text.substr(m.position(0) + m.length(0));
          if (after.compare(0, filename.size() + 1, filename + ">") != 0 &&
              after.compare(0, filename.size() + 1, filename + ":") != 0)
            throw;
          const unsigned int line = std::stoul(m[1]);
          const std::string  why =
            DeclaredParameters(prm).explain_line(filename, line);
          if (why.empty())
            throw;
          const bool ends = why.back() == '?' || why.back() == '.';
          AssertThrow(false,
                      dealii::ExcMessage(filename + ":" + std::to_string(line) +
                                         ": " + why + (ends ? "" : ".")));
        }
    }
  } // namespace app
} // namespace cycloid
