"""Friction laws handed to finite-element codes: Abaqus user routines (FRIC, VFRIC,
VFRICTION) generated from gauge files, and GetFEM runs of the strip assembly."""
