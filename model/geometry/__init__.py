"""The exact geometry core, one sub-package per stage of the pipeline (docs/adr/0030).

=================  ==========================================================================================
``discretize``     D in the three models: float64 polygons (``discretize``), the exact predicates (``exact``),
                   polygons with rational vertices (``exact_shape``, ``rational``, ``rational_kernels``).
``topology``       connected components of pixel sets (``labeling``) and their crack boundaries (``cracks``).
``dss``            digital straight segments (``Segment``), their preimages and the segmentation of chains.
``reconstruct``    R: the corridor of every ring and the exact vertex search (``_corridor`` … ``_straighten``,
                   run by ``_kernels``), its verification and safety net, and the watertight subdivision of a
                   label map (``subdivision``, ``polygonize``).
``hausdorff``      the exact Hausdorff distance and the paper's error bounds (``bounds``).
``polyhedra``      the 3-D Euclidean solid (``Polyhedron``), validated exactly with filtered orient3d/orient2d
                   (``predicates``), and its explicit ``repair``.
=================  ==========================================================================================

Each stage's main function is importable from the package itself: ``mrm.geometry.discretize.discretize``,
``mrm.geometry.reconstruct.reconstruct``, ``mrm.geometry.hausdorff.hausdorff_distance``; ``_jit`` is the
one numba entry point of every kernel.
"""
