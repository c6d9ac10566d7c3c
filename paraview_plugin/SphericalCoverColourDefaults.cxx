// SPDX-License-Identifier: BSD-3-Clause
#include "SphericalCoverColourDefaults.h"

#include <vtkSMSettings.h>

void SphericalCoverRegisterColourDefaults()
{
  // Loading the plug-in twice (Tools > Manage Plugins) must not stack collections.
  static bool registered = false;
  if (registered)
  {
    return;
  }
  registered = true;
  // The path is the array's name, the lookup table proxy's XML name (PVLookupTable), then its
  // properties' XML names (IndexedLookup is Python's InterpretValuesAsCategories);
  // AnnotationsInitialized keeps ParaView from replacing the names with the data's values.
  vtkSMSettings::GetInstance()->AddCollectionFromString(R"json({
  "array_lookup_tables": {
    "SplitReason": {
      "PVLookupTable": {
        "IndexedLookup": 1,
        "AnnotationsInitialized": 1,
        "Annotations": ["0", "none", "1", "self-shadowing", "2", "hemispherical containment",
                        "3", "spherical shape", "4", "characterisability"],
        "IndexedColors": [0.85, 0.85, 0.85, 0.30, 0.75, 0.75, 0.95, 0.85, 0.30,
                          0.85, 0.35, 0.30, 0.45, 0.40, 0.80]
      }
    }
  }
})json",
    0.0);
}
