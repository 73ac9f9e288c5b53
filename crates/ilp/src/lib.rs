//! invlight-ilp (to be written).
