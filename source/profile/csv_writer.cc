#include <deal.II/base/exceptions.h>

#include <cycloid/profile/csv_writer.h>

#include <fstream>
#include <iomanip>

namespace cycloid
{
  namespace profile
  {
    void
    write_csv(const DiscOutline &outline, const std::string &filename)
    {
      std::ofstream out(filename);
      AssertThrow(out.good(),
                  dealii::ExcMessage("cannot write '" + filename +
                                     "' (check Output directory)."));
      out << std::setprecision(15) << "x_mm,y_mm\n";
      for (const auto &v : outline.vertices)
        out << v[0] << ',' << v[1] << '\n';
      if (!outline.vertices.empty())
        out << outline.vertices[0][0] << ',' << outline.vertices[0][1] << '\n';
      out.close();
      AssertThrow(!out.fail(),
                  dealii::ExcMessage("writing '" + filename + "' failed."));
    }
  } // namespace profile
} // namespace cycloid
