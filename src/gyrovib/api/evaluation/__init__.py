"""The model evaluated on a prepared Study, and the immutable results of the views.

==========================================  =====================================
module                                      what it holds
==========================================  =====================================
:mod:`gyrovib.api.evaluation.evaluate`      the sensor forms, the error loop over
                                            the groups (``errors``), saturation
:mod:`gyrovib.api.evaluation.results`       the result types of analyze, sweep,
                                            bounds and select (``Result``)
==========================================  =====================================
"""
