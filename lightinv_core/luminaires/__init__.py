"""Luminaire photometry: IES LM-63 and EULUMDAT files, analytic distributions, the catalogue."""
