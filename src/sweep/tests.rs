//! Tests of the sweep: study files, templates, the merge, the plot.
