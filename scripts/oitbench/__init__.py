"""oitbench's Python library: the scripts' one reader, case key, techniques, statistics, paper tables,
figures and result store. The programs in scripts/ are thin command lines on top of it; no script
imports another script."""
