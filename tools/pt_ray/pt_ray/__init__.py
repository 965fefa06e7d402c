"""pt_ray: distributed pt renders on a Ray cluster.

A render of N samples per pixel is cut into K contiguous sample ranges of the global sequence;
each range is a Ray task running `pt render --samples A:B`, and `pt merge` sums the parts into
the image a single `pt render --spp N` makes (see README, "Rendering on a cluster").
"""
