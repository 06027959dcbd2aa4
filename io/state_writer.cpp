#include "io/state_writer.h"

#include "io/output_file.h"

namespace fibra {

void writeState(const std::string& path, const FibreStore& fs, const Eigen::VectorXd& q) {
  OutputFile file(path);
  std::string text = "fibre,node,x,y,z,g1x,g1y,g1z,g2x,g2y,g2z\n";
  for (Index f = 0; f < fs.fibres(); ++f)
    for (Index i = 0; i < fs.nodeCount[f]; ++i) {
      text += fs.name[f] + "," + std::to_string(i);
      const Index n = fs.firstNode[f] + i;
      for (int k = 0; k < kNodeDofs; ++k) {
        text += ',';
        appendNumber(text, q(kNodeDofs * n + k));
      }
      text += '\n';
    }
  file.stream() << text;
  file.commit();
}

}  // namespace fibra
