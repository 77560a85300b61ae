// Never a crash: thousands of random byte edits of valid CL text give either
// events or a ClError (the writer may add an OutputError), nothing else.
#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "postproc/cldata/cl_reader.h"
#include "postproc/output/gcode_writer.h"

namespace vcpost::cldata {
namespace {

const char* const seed_text =
    "PARTNO CORE_WORK\nUNITS / INCHES\nLOADTL / 8\n$$-> CUTTER / 0.375000\n"
    "SPINDL / RPM, 2000.000000,  CLW\nFROM / 0.0000, 0.0000, 3.7750\nRAPID\n"
    "GOTO / 7.4300, 5.8500, 3.7750\nFEDRAT / 10.000000,  IPM\n"
    "CIRCLE / 7.4550, 5.8500, 1.8000,  $\n0.0000, 0.0000, 1.0000,  0.0250\n"
    "GOTO / 7.4675, 5.8283, 1.8000\n       7.4675, 5.8717, 1.8000\n"
    "UNITS/MM\nGOTO/-254.9774,466.5681,206.8891\nNURBS/\nKNOT/0.0416667,0.375,0.625,0.9583333,1.0\n"
    "CNTRL/-254.9774,466.2698,206.9401\nCNTRL/-254.9775,463.5692,207.2380\n"
    "CNTRL/-254.9776,459.2589,209.0136\nCNTRL/-254.9778,454.6135,213.9021\n"
    "CNTRL/-254.9779,453.0599,218.2973\nCNTRL/-254.9779,452.9000,221.0096\n"
    "CNTRL/-254.9779,452.8642,221.3100\nCYCLE/DRILL,FEDTO,10.,MMPM,275.59,RAPTO,3.,RTRCTO,25.\n"
    "GOTO/29.06066,116.93934,0\nCYCLE/OFF\nCUTTER/4.,0,2.,1.201721,31.,0,83.\n"
    "GOTO/1,2,3\nCIRCLE/0,0,3,0,1,1,1.7320508\nGOTO/1,-2,3\nDELAY/1\nCOOLNT/FLOOD\nFINI\n";

TEST(ClFuzz, RandomEditsGiveEventsOrClErrorOnly) {
  std::mt19937 rng(20240601);
  const std::string base = seed_text;
  using namespace std::string_literals;
  const std::string alphabet = "0123456789.,-+/$ \nEeGOTCIRLXNa\t\r\0\xff"s;
  int errors = 0, successes = 0;
  for (int round = 0; round < 3000; ++round) {
    std::string text = base;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < edits; ++k) {
      const std::size_t at = rng() % text.size();
      const char c = alphabet[rng() % alphabet.size()];
      switch (rng() % 3) {
        case 0:
          text[at] = c;
          break;
        case 1:
          text.insert(text.begin() + static_cast<std::ptrdiff_t>(at), c);
          break;
        default:
          text.erase(at, 1 + rng() % 8);
          break;
      }
      if (text.empty()) text = "X";
    }
    std::istringstream in(text);
    ClReader reader(in, "fuzz.cl");
    std::ostringstream out;
    output::GcodeWriter writer(out, output::Format{});
    try {
      while (auto e = reader.next()) writer.write(*e);
      writer.finish();
      ++successes;
    } catch (const ClError&) {
      ++errors;
    } catch (const output::OutputError&) {
      ++errors;
    } catch (const std::exception& e) {
      FAIL() << "unexpected exception " << e.what() << " for:\n" << text;
    }
  }
  EXPECT_GT(errors, 100);
  EXPECT_GT(successes, 10);  // edits in comments, spacing, PARTNO text
}

}  // namespace
}  // namespace vcpost::cldata
