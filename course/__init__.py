"""The course's own tooling, outside the installable library: executing the lessons, the
course build (site, slides, figures, student edition), the lab launcher, the portability
check and the maintainers' scripts.  Run from the repository root, e.g.
``python -m course.build`` (``make course``); see the Makefile.

=======================  ======================================================
``course.notebooks``     what every tool reads in a lesson: solution markers, tags
``course.execute``       execute lessons in a fresh kernel (``make lessons``)
``course.build``         the course site, slides, figures, student edition
``course.figures``       the figure export (``make figures``) and the gallery
``course.slides``        the offline reveal.js decks
``course.student``       the student edition
``course.lab``           JupyterLab on 127.0.0.1 with a token (``make lab``)
``course.portable``      re-execute lessons under another BLAS/SIMD selection
``course.pins``          write ``requirements/constraints.txt`` (a freeze + overrides)
``course.wheels``        resolve lab/book/binder from wheels per platform and Python
``course.fetch_structures``  fetch and verify the shipped PDB structures
``course.example_pdb``   rewrite the shipped example molecule, shapelab/data/globule.pdb
=======================  ======================================================
"""
