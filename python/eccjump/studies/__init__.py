"""Studies built on the classification and the motion: experiment design (``design``), the
uncertainty of a prediction (``uncertainty``) and the analysis of a measured run
(``experiment``). Deliberately empty: the functions ``eccjump.design`` and
``eccjump.uncertainty`` are public at the top, so no name here shadows a subpackage."""
