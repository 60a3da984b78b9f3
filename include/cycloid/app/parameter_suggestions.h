#ifndef cycloid_app_parameter_suggestions_h
#define cycloid_app_parameter_suggestions_h

#include <deal.II/base/parameter_handler.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include <boost/property_tree/ptree_fwd.hpp>

namespace cycloid
{
  namespace app
  {
    /**
     * @brief The names a ParameterHandler declares (subsections, entries,
     * the pattern of each entry), and the messages that explain a line of a
     * parameter file that deal.II rejected: the misspelled name, where it
     * was, and the closest declared names ("did you mean ...?").
     *
     * deal.II's own parse errors name the line but not what was meant
     * ("No entry with name <Tooth widht> was declared in the current
     * subsection"). The handler is only asked for its declarations (printed
     * as JSON and read back), so the suggestions always follow what the
     * code declares.
     */
    class DeclaredParameters
    {
    public:
      /** Read the declarations of @p prm (its values are not used). */
      explicit DeclaredParameters(const dealii::ParameterHandler &prm);

      /**
       * Explain why line @p line_number of the parameter file @p filename
       * was rejected, or return "" if that line looks valid (then the
       * caller keeps deal.II's message). The subsection path is followed
       * from the first line, with deal.II's rules (comments, `\`
       * continuation lines).
       */
      std::string
      explain_line(const std::string &filename,
                   const unsigned int line_number) const;

      /**
       * Up to @p n_max of @p candidates closest to @p name
       * (case-insensitive edit distance with transpositions, within about a
       * third of the name's length, or containing the name), closest first.
       */
      static std::vector<std::string>
      closest(const std::string              &name,
              const std::vector<std::string> &candidates,
              const unsigned int              n_max = 3);

      /**
       * Every declared entry, as its subsection path followed by its name
       * ({"Mesh", "Contact refinements"}), subsections depth first, each in
       * declaration order.
       */
      std::vector<std::vector<std::string>>
      entries() const;

    private:
      /** One subsection: its entries (with their patterns) and children. */
      struct Section
      {
        /** Entry names in declaration order. */
        std::vector<std::string> entries;
        /** The pattern description of each entry. */
        std::vector<std::string> patterns;
        /** Subsection names in declaration order. */
        std::vector<std::string> names;
        /** The subsections, in the order of `names`. */
        std::vector<Section> children;
      };

      /** Fill @p section from the JSON tree @p tree. */
      static void
      read_section(const boost::property_tree::ptree &tree, Section &section);

      /** The section at @p path, or nullptr if it is not declared. */
      const Section *
      find(const std::vector<std::string> &path) const;

      /** "subsection 'A/B'" or "the top level" for @p path. */
      static std::string
      where(const std::vector<std::string> &path);

      /** Every declared place of an entry (or, if @p subsection, of a
       * subsection) spelled @p name in any case. */
      std::vector<std::vector<std::string>>
      places_of(const std::string &name, const bool subsection) const;

      /** The text for an undeclared @p name (an entry or, if
       * @p subsection, a subsection) at @p path. */
      std::string
      explain_unknown(const std::string              &name,
                      const std::vector<std::string> &path,
                      const bool                      subsection) const;

      /** The text for @p value of entry @p name at @p path if it does not
       * match the entry's pattern, else "". */
      std::string
      explain_value(const std::string              &name,
                    const std::string              &value,
                    const std::vector<std::string> &path) const;

      /** The top level. */
      Section top;
    };

    /**
     * Read @p filename into @p prm, like ParameterHandler::parse_input().
     * If deal.II rejects a line (an undeclared subsection or entry, a value
     * that does not match its pattern), the exception it throws is
     * replaced by one whose message names the file, the line, the
     * subsection and the closest declared names (DeclaredParameters);
     * other errors pass unchanged.
     */
    void
    parse_input_explained(dealii::ParameterHandler &prm,
                          const std::string        &filename);

    /**
     * The logical lines of the parameter file @p filename as
     * ParameterHandler::parse_input() reads them: trimmed, without
     * comments, tabs as spaces, a line ending in a backslash joined with the
     * next; each with the number of its first physical line.
     */
    std::vector<std::pair<unsigned int, std::string>>
    logical_lines(const std::string &filename);

    /**
     * Record the entries a parameter file sets: attach to every entry that
     * @p prm declares an action (ParameterHandler::add_action()) that
     * stores its value in @p set under "Subsection/Entry" ("Entry" at the
     * top level, "A/B/Entry" in a nested subsection) whenever
     * parse_input() (or set()) gives it one. deal.II does not otherwise tell
     * whether a value came from the file or is the default; the actions see
     * what deal.II read, `include`d files and continuation lines as well.
     * deal.II runs each action once with the default when it is attached;
     * @p set is cleared after that, so after parsing it holds exactly the
     * entries set, each with its last value. @p set must outlive @p prm's
     * parsing.
     */
    void
    record_entries_set(dealii::ParameterHandler           &prm,
                       std::map<std::string, std::string> &set);
  } // namespace app
} // namespace cycloid

#endif
