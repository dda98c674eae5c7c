"""The engine of shapelab: exact predicates, certificates, tie-breaks and fast kernels behind the public core's seams (not required reading)."""
