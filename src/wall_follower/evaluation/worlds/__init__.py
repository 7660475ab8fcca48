"""Generated worlds: floorplans drawn exactly, the generator, the checks every world passes."""
