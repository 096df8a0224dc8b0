"""Reports: the text table and JSON of a result, the check report (text, JSON, HTML) and
the optimisation report. Renders what the solver and the studies computed; solves nothing."""
