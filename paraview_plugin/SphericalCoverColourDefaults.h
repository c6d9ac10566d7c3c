// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SphericalCoverColourDefaults.h
 * @brief The plug-in's defaults for the colour maps of its categorical arrays, registered when
 * ParaView loads the plug-in (paraview_add_plugin's INITIALIZERS).
 *
 * ParaView chooses a colour map by array name: vtkSMTransferFunctionManager creates the lookup
 * table of an array and loads the settings under ".array_lookup_tables.<array name>" (what
 * "Save as default for arrays named ..." writes). ParaView registers its own array defaults
 * the same way, as a settings collection of priority 0 (vtkInitializationHelper: the block
 * colours' preset), below the site (1) and user settings (highest), so a user's own choice
 * still wins. No server-manager XML hint names a colour map in ParaView 5.11.
 *
 * SplitReason (vtkIntervalSubdivisionFilter's Patches) is a category, not a quantity: which
 * criterion of paper §4.2 caused a patch's last split. Its default map is categorical with one
 * named colour per criterion, the colours of example 1.
 */
#ifndef SphericalCoverColourDefaults_h
#define SphericalCoverColourDefaults_h

/// Adds the plug-in's colour-map defaults to ParaView's settings (once per process).
void SphericalCoverRegisterColourDefaults();

#endif
