/* dem_module.h - the FEM-DEM granular bending scene as the CLI sees it (trigger section
 * [grains]). Linking this never loads LIGGGHTS: the run is a plugin (dem_scene.h). */
#ifndef DEM_MODULE_H
#define DEM_MODULE_H

#include "sa_module.h"

extern const SaModule dem_module;

#endif
