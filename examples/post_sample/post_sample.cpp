// Posts a finishing program through libvcpost: `vcpost post` as a call.
// usage: post_sample PROGRAM MODEL [MACHINE] > posted.nc
#include <vcpost/post.h>
#include <vcpost/version.h>

#include <fstream>
#include <iostream>
#include <sstream>

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: post_sample PROGRAM MODEL [MACHINE] > posted.nc\n";
    return 2;
  }
  namespace vc = vcpost::api;
  try {
    std::ifstream in(argv[1], std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    const vc::Model model = vc::Model::load(argv[2]);
    const vc::MachineProfile machine = vc::MachineProfile::load(argc > 3 ? argv[3] : "generic");
    vc::PostOptions options;
    options.tool = "ball:10";  // mm
    options.vc = 120;          // m/min
    options.ap = 0.3;          // mm
    const vc::PostResult result = vc::post(text.str(), argv[1], model, machine, options);
    std::cout << result.program;
    std::cerr << vc::version_line() << ": " << result.summary.points << " points, "
              << result.summary.s_words << " S words written\n";
  } catch (const vc::Error& e) {  // the only exception the library throws
    std::cerr << "post_sample: " << e.what() << '\n';
    return 2;
  }
  return 0;
}
