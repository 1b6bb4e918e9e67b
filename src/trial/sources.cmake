# Sources of the trial layer
