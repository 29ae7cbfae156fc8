// coin-count: the triangles Coin makes of each scene file, as the reference for our readers.
//
// Usage: coin-count FILE...; prints one line per file: "FILE<TAB>TRIANGLES<TAB>DEGENERATE<TAB>SKIPPED":
// the triangles SoCallbackAction generates leaving out text and NURBS shapes (which our
// readers skip, and whose tessellation needs an OpenGL context), how many of them have zero
// area (our readers drop those), and how many text and NURBS shapes were left out; or "FILE<TAB>unreadable" when Coin cannot read the file.
// Built by tools/check/coin-count/build; tools/check/coin-table compares these counts with ours.

#include <Inventor/SoDB.h>
#include <Inventor/SoInput.h>
#include <Inventor/SoPrimitiveVertex.h>
#include <Inventor/actions/SoCallbackAction.h>
#include <Inventor/nodekits/SoNodeKit.h>
#include <Inventor/nodes/SoAsciiText.h>
#include <Inventor/nodes/SoIndexedNurbsSurface.h>
#include <Inventor/nodes/SoNurbsSurface.h>
#include <Inventor/nodes/SoSeparator.h>
#include <Inventor/nodes/SoShape.h>
#include <Inventor/nodes/SoText3.h>
#include <Inventor/VRMLnodes/SoVRMLText.h>

#include <cstdio>

namespace {

struct Counts {
  unsigned long triangles = 0;
  unsigned long degenerate = 0;
  unsigned long skipped = 0;
};

// Counts a triangle, and whether its area is zero (corners on one line).
void triangle(void *data, SoCallbackAction *, const SoPrimitiveVertex *a,
              const SoPrimitiveVertex *b, const SoPrimitiveVertex *c) {
  Counts *counts = static_cast<Counts *>(data);
  counts->triangles += 1;
  const SbVec3f u = b->getPoint() - a->getPoint();
  const SbVec3f v = c->getPoint() - a->getPoint();
  const float scale = u.sqrLength() * v.sqrLength();
  if (u.cross(v).sqrLength() <= 1e-12f * scale) {
    counts->degenerate += 1;
  }
}

// Leaves a text or NURBS shape out of the traversal, counting it.
SoCallbackAction::Response skip(void *data, SoCallbackAction *, const SoNode *) {
  static_cast<Counts *>(data)->skipped += 1;
  return SoCallbackAction::PRUNE;
}

}  // namespace

int main(int argc, char **argv) {
  SoDB::init();
  SoNodeKit::init();
  for (int i = 1; i < argc; i++) {
    SoInput in;
    SoSeparator *root = nullptr;
    if (in.openFile(argv[i])) {
      root = SoDB::readAll(&in);
    }
    if (root == nullptr) {
      std::printf("%s\tunreadable\n", argv[i]);
      continue;
    }
    root->ref();
    Counts counts;
    SoCallbackAction action;
    action.addTriangleCallback(SoShape::getClassTypeId(), triangle, &counts);
    const SoType skipped[] = {
        SoText3::getClassTypeId(),         SoAsciiText::getClassTypeId(),
        SoVRMLText::getClassTypeId(),      SoNurbsSurface::getClassTypeId(),
        SoIndexedNurbsSurface::getClassTypeId()};
    for (const SoType &t : skipped) {
      action.addPreCallback(t, skip, &counts);
    }
    action.apply(root);
    std::printf("%s\t%lu\t%lu\t%lu\n", argv[i], counts.triangles, counts.degenerate,
                counts.skipped);
    root->unref();
  }
  return 0;
}
