use canopen_od_derive::ObjectDictionary;

// A compact dictionary names each row's shape (data type, access, PDO mapping, count, limits) in one
// byte: 257 VARs that differ only in their high limit are one shape too many.
#[derive(ObjectDictionary, Default)]
#[od(compact)]
struct App {
    #[od(index = 0x2000, max = 1)]
    v0: u16,
    #[od(index = 0x2001, max = 2)]
    v1: u16,
    #[od(index = 0x2002, max = 3)]
    v2: u16,
    #[od(index = 0x2003, max = 4)]
    v3: u16,
    #[od(index = 0x2004, max = 5)]
    v4: u16,
    #[od(index = 0x2005, max = 6)]
    v5: u16,
    #[od(index = 0x2006, max = 7)]
    v6: u16,
    #[od(index = 0x2007, max = 8)]
    v7: u16,
    #[od(index = 0x2008, max = 9)]
    v8: u16,
    #[od(index = 0x2009, max = 10)]
    v9: u16,
    #[od(index = 0x200A, max = 11)]
    v10: u16,
    #[od(index = 0x200B, max = 12)]
    v11: u16,
    #[od(index = 0x200C, max = 13)]
    v12: u16,
    #[od(index = 0x200D, max = 14)]
    v13: u16,
    #[od(index = 0x200E, max = 15)]
    v14: u16,
    #[od(index = 0x200F, max = 16)]
    v15: u16,
    #[od(index = 0x2010, max = 17)]
    v16: u16,
    #[od(index = 0x2011, max = 18)]
    v17: u16,
    #[od(index = 0x2012, max = 19)]
    v18: u16,
    #[od(index = 0x2013, max = 20)]
    v19: u16,
    #[od(index = 0x2014, max = 21)]
    v20: u16,
    #[od(index = 0x2015, max = 22)]
    v21: u16,
    #[od(index = 0x2016, max = 23)]
    v22: u16,
    #[od(index = 0x2017, max = 24)]
    v23: u16,
    #[od(index = 0x2018, max = 25)]
    v24: u16,
    #[od(index = 0x2019, max = 26)]
    v25: u16,
    #[od(index = 0x201A, max = 27)]
    v26: u16,
    #[od(index = 0x201B, max = 28)]
    v27: u16,
    #[od(index = 0x201C, max = 29)]
    v28: u16,
    #[od(index = 0x201D, max = 30)]
    v29: u16,
    #[od(index = 0x201E, max = 31)]
    v30: u16,
    #[od(index = 0x201F, max = 32)]
    v31: u16,
    #[od(index = 0x2020, max = 33)]
    v32: u16,
    #[od(index = 0x2021, max = 34)]
    v33: u16,
    #[od(index = 0x2022, max = 35)]
    v34: u16,
    #[od(index = 0x2023, max = 36)]
    v35: u16,
    #[od(index = 0x2024, max = 37)]
    v36: u16,
    #[od(index = 0x2025, max = 38)]
    v37: u16,
    #[od(index = 0x2026, max = 39)]
    v38: u16,
    #[od(index = 0x2027, max = 40)]
    v39: u16,
    #[od(index = 0x2028, max = 41)]
    v40: u16,
    #[od(index = 0x2029, max = 42)]
    v41: u16,
    #[od(index = 0x202A, max = 43)]
    v42: u16,
    #[od(index = 0x202B, max = 44)]
    v43: u16,
    #[od(index = 0x202C, max = 45)]
    v44: u16,
    #[od(index = 0x202D, max = 46)]
    v45: u16,
    #[od(index = 0x202E, max = 47)]
    v46: u16,
    #[od(index = 0x202F, max = 48)]
    v47: u16,
    #[od(index = 0x2030, max = 49)]
    v48: u16,
    #[od(index = 0x2031, max = 50)]
    v49: u16,
    #[od(index = 0x2032, max = 51)]
    v50: u16,
    #[od(index = 0x2033, max = 52)]
    v51: u16,
    #[od(index = 0x2034, max = 53)]
    v52: u16,
    #[od(index = 0x2035, max = 54)]
    v53: u16,
    #[od(index = 0x2036, max = 55)]
    v54: u16,
    #[od(index = 0x2037, max = 56)]
    v55: u16,
    #[od(index = 0x2038, max = 57)]
    v56: u16,
    #[od(index = 0x2039, max = 58)]
    v57: u16,
    #[od(index = 0x203A, max = 59)]
    v58: u16,
    #[od(index = 0x203B, max = 60)]
    v59: u16,
    #[od(index = 0x203C, max = 61)]
    v60: u16,
    #[od(index = 0x203D, max = 62)]
    v61: u16,
    #[od(index = 0x203E, max = 63)]
    v62: u16,
    #[od(index = 0x203F, max = 64)]
    v63: u16,
    #[od(index = 0x2040, max = 65)]
    v64: u16,
    #[od(index = 0x2041, max = 66)]
    v65: u16,
    #[od(index = 0x2042, max = 67)]
    v66: u16,
    #[od(index = 0x2043, max = 68)]
    v67: u16,
    #[od(index = 0x2044, max = 69)]
    v68: u16,
    #[od(index = 0x2045, max = 70)]
    v69: u16,
    #[od(index = 0x2046, max = 71)]
    v70: u16,
    #[od(index = 0x2047, max = 72)]
    v71: u16,
    #[od(index = 0x2048, max = 73)]
    v72: u16,
    #[od(index = 0x2049, max = 74)]
    v73: u16,
    #[od(index = 0x204A, max = 75)]
    v74: u16,
    #[od(index = 0x204B, max = 76)]
    v75: u16,
    #[od(index = 0x204C, max = 77)]
    v76: u16,
    #[od(index = 0x204D, max = 78)]
    v77: u16,
    #[od(index = 0x204E, max = 79)]
    v78: u16,
    #[od(index = 0x204F, max = 80)]
    v79: u16,
    #[od(index = 0x2050, max = 81)]
    v80: u16,
    #[od(index = 0x2051, max = 82)]
    v81: u16,
    #[od(index = 0x2052, max = 83)]
    v82: u16,
    #[od(index = 0x2053, max = 84)]
    v83: u16,
    #[od(index = 0x2054, max = 85)]
    v84: u16,
    #[od(index = 0x2055, max = 86)]
    v85: u16,
    #[od(index = 0x2056, max = 87)]
    v86: u16,
    #[od(index = 0x2057, max = 88)]
    v87: u16,
    #[od(index = 0x2058, max = 89)]
    v88: u16,
    #[od(index = 0x2059, max = 90)]
    v89: u16,
    #[od(index = 0x205A, max = 91)]
    v90: u16,
    #[od(index = 0x205B, max = 92)]
    v91: u16,
    #[od(index = 0x205C, max = 93)]
    v92: u16,
    #[od(index = 0x205D, max = 94)]
    v93: u16,
    #[od(index = 0x205E, max = 95)]
    v94: u16,
    #[od(index = 0x205F, max = 96)]
    v95: u16,
    #[od(index = 0x2060, max = 97)]
    v96: u16,
    #[od(index = 0x2061, max = 98)]
    v97: u16,
    #[od(index = 0x2062, max = 99)]
    v98: u16,
    #[od(index = 0x2063, max = 100)]
    v99: u16,
    #[od(index = 0x2064, max = 101)]
    v100: u16,
    #[od(index = 0x2065, max = 102)]
    v101: u16,
    #[od(index = 0x2066, max = 103)]
    v102: u16,
    #[od(index = 0x2067, max = 104)]
    v103: u16,
    #[od(index = 0x2068, max = 105)]
    v104: u16,
    #[od(index = 0x2069, max = 106)]
    v105: u16,
    #[od(index = 0x206A, max = 107)]
    v106: u16,
    #[od(index = 0x206B, max = 108)]
    v107: u16,
    #[od(index = 0x206C, max = 109)]
    v108: u16,
    #[od(index = 0x206D, max = 110)]
    v109: u16,
    #[od(index = 0x206E, max = 111)]
    v110: u16,
    #[od(index = 0x206F, max = 112)]
    v111: u16,
    #[od(index = 0x2070, max = 113)]
    v112: u16,
    #[od(index = 0x2071, max = 114)]
    v113: u16,
    #[od(index = 0x2072, max = 115)]
    v114: u16,
    #[od(index = 0x2073, max = 116)]
    v115: u16,
    #[od(index = 0x2074, max = 117)]
    v116: u16,
    #[od(index = 0x2075, max = 118)]
    v117: u16,
    #[od(index = 0x2076, max = 119)]
    v118: u16,
    #[od(index = 0x2077, max = 120)]
    v119: u16,
    #[od(index = 0x2078, max = 121)]
    v120: u16,
    #[od(index = 0x2079, max = 122)]
    v121: u16,
    #[od(index = 0x207A, max = 123)]
    v122: u16,
    #[od(index = 0x207B, max = 124)]
    v123: u16,
    #[od(index = 0x207C, max = 125)]
    v124: u16,
    #[od(index = 0x207D, max = 126)]
    v125: u16,
    #[od(index = 0x207E, max = 127)]
    v126: u16,
    #[od(index = 0x207F, max = 128)]
    v127: u16,
    #[od(index = 0x2080, max = 129)]
    v128: u16,
    #[od(index = 0x2081, max = 130)]
    v129: u16,
    #[od(index = 0x2082, max = 131)]
    v130: u16,
    #[od(index = 0x2083, max = 132)]
    v131: u16,
    #[od(index = 0x2084, max = 133)]
    v132: u16,
    #[od(index = 0x2085, max = 134)]
    v133: u16,
    #[od(index = 0x2086, max = 135)]
    v134: u16,
    #[od(index = 0x2087, max = 136)]
    v135: u16,
    #[od(index = 0x2088, max = 137)]
    v136: u16,
    #[od(index = 0x2089, max = 138)]
    v137: u16,
    #[od(index = 0x208A, max = 139)]
    v138: u16,
    #[od(index = 0x208B, max = 140)]
    v139: u16,
    #[od(index = 0x208C, max = 141)]
    v140: u16,
    #[od(index = 0x208D, max = 142)]
    v141: u16,
    #[od(index = 0x208E, max = 143)]
    v142: u16,
    #[od(index = 0x208F, max = 144)]
    v143: u16,
    #[od(index = 0x2090, max = 145)]
    v144: u16,
    #[od(index = 0x2091, max = 146)]
    v145: u16,
    #[od(index = 0x2092, max = 147)]
    v146: u16,
    #[od(index = 0x2093, max = 148)]
    v147: u16,
    #[od(index = 0x2094, max = 149)]
    v148: u16,
    #[od(index = 0x2095, max = 150)]
    v149: u16,
    #[od(index = 0x2096, max = 151)]
    v150: u16,
    #[od(index = 0x2097, max = 152)]
    v151: u16,
    #[od(index = 0x2098, max = 153)]
    v152: u16,
    #[od(index = 0x2099, max = 154)]
    v153: u16,
    #[od(index = 0x209A, max = 155)]
    v154: u16,
    #[od(index = 0x209B, max = 156)]
    v155: u16,
    #[od(index = 0x209C, max = 157)]
    v156: u16,
    #[od(index = 0x209D, max = 158)]
    v157: u16,
    #[od(index = 0x209E, max = 159)]
    v158: u16,
    #[od(index = 0x209F, max = 160)]
    v159: u16,
    #[od(index = 0x20A0, max = 161)]
    v160: u16,
    #[od(index = 0x20A1, max = 162)]
    v161: u16,
    #[od(index = 0x20A2, max = 163)]
    v162: u16,
    #[od(index = 0x20A3, max = 164)]
    v163: u16,
    #[od(index = 0x20A4, max = 165)]
    v164: u16,
    #[od(index = 0x20A5, max = 166)]
    v165: u16,
    #[od(index = 0x20A6, max = 167)]
    v166: u16,
    #[od(index = 0x20A7, max = 168)]
    v167: u16,
    #[od(index = 0x20A8, max = 169)]
    v168: u16,
    #[od(index = 0x20A9, max = 170)]
    v169: u16,
    #[od(index = 0x20AA, max = 171)]
    v170: u16,
    #[od(index = 0x20AB, max = 172)]
    v171: u16,
    #[od(index = 0x20AC, max = 173)]
    v172: u16,
    #[od(index = 0x20AD, max = 174)]
    v173: u16,
    #[od(index = 0x20AE, max = 175)]
    v174: u16,
    #[od(index = 0x20AF, max = 176)]
    v175: u16,
    #[od(index = 0x20B0, max = 177)]
    v176: u16,
    #[od(index = 0x20B1, max = 178)]
    v177: u16,
    #[od(index = 0x20B2, max = 179)]
    v178: u16,
    #[od(index = 0x20B3, max = 180)]
    v179: u16,
    #[od(index = 0x20B4, max = 181)]
    v180: u16,
    #[od(index = 0x20B5, max = 182)]
    v181: u16,
    #[od(index = 0x20B6, max = 183)]
    v182: u16,
    #[od(index = 0x20B7, max = 184)]
    v183: u16,
    #[od(index = 0x20B8, max = 185)]
    v184: u16,
    #[od(index = 0x20B9, max = 186)]
    v185: u16,
    #[od(index = 0x20BA, max = 187)]
    v186: u16,
    #[od(index = 0x20BB, max = 188)]
    v187: u16,
    #[od(index = 0x20BC, max = 189)]
    v188: u16,
    #[od(index = 0x20BD, max = 190)]
    v189: u16,
    #[od(index = 0x20BE, max = 191)]
    v190: u16,
    #[od(index = 0x20BF, max = 192)]
    v191: u16,
    #[od(index = 0x20C0, max = 193)]
    v192: u16,
    #[od(index = 0x20C1, max = 194)]
    v193: u16,
    #[od(index = 0x20C2, max = 195)]
    v194: u16,
    #[od(index = 0x20C3, max = 196)]
    v195: u16,
    #[od(index = 0x20C4, max = 197)]
    v196: u16,
    #[od(index = 0x20C5, max = 198)]
    v197: u16,
    #[od(index = 0x20C6, max = 199)]
    v198: u16,
    #[od(index = 0x20C7, max = 200)]
    v199: u16,
    #[od(index = 0x20C8, max = 201)]
    v200: u16,
    #[od(index = 0x20C9, max = 202)]
    v201: u16,
    #[od(index = 0x20CA, max = 203)]
    v202: u16,
    #[od(index = 0x20CB, max = 204)]
    v203: u16,
    #[od(index = 0x20CC, max = 205)]
    v204: u16,
    #[od(index = 0x20CD, max = 206)]
    v205: u16,
    #[od(index = 0x20CE, max = 207)]
    v206: u16,
    #[od(index = 0x20CF, max = 208)]
    v207: u16,
    #[od(index = 0x20D0, max = 209)]
    v208: u16,
    #[od(index = 0x20D1, max = 210)]
    v209: u16,
    #[od(index = 0x20D2, max = 211)]
    v210: u16,
    #[od(index = 0x20D3, max = 212)]
    v211: u16,
    #[od(index = 0x20D4, max = 213)]
    v212: u16,
    #[od(index = 0x20D5, max = 214)]
    v213: u16,
    #[od(index = 0x20D6, max = 215)]
    v214: u16,
    #[od(index = 0x20D7, max = 216)]
    v215: u16,
    #[od(index = 0x20D8, max = 217)]
    v216: u16,
    #[od(index = 0x20D9, max = 218)]
    v217: u16,
    #[od(index = 0x20DA, max = 219)]
    v218: u16,
    #[od(index = 0x20DB, max = 220)]
    v219: u16,
    #[od(index = 0x20DC, max = 221)]
    v220: u16,
    #[od(index = 0x20DD, max = 222)]
    v221: u16,
    #[od(index = 0x20DE, max = 223)]
    v222: u16,
    #[od(index = 0x20DF, max = 224)]
    v223: u16,
    #[od(index = 0x20E0, max = 225)]
    v224: u16,
    #[od(index = 0x20E1, max = 226)]
    v225: u16,
    #[od(index = 0x20E2, max = 227)]
    v226: u16,
    #[od(index = 0x20E3, max = 228)]
    v227: u16,
    #[od(index = 0x20E4, max = 229)]
    v228: u16,
    #[od(index = 0x20E5, max = 230)]
    v229: u16,
    #[od(index = 0x20E6, max = 231)]
    v230: u16,
    #[od(index = 0x20E7, max = 232)]
    v231: u16,
    #[od(index = 0x20E8, max = 233)]
    v232: u16,
    #[od(index = 0x20E9, max = 234)]
    v233: u16,
    #[od(index = 0x20EA, max = 235)]
    v234: u16,
    #[od(index = 0x20EB, max = 236)]
    v235: u16,
    #[od(index = 0x20EC, max = 237)]
    v236: u16,
    #[od(index = 0x20ED, max = 238)]
    v237: u16,
    #[od(index = 0x20EE, max = 239)]
    v238: u16,
    #[od(index = 0x20EF, max = 240)]
    v239: u16,
    #[od(index = 0x20F0, max = 241)]
    v240: u16,
    #[od(index = 0x20F1, max = 242)]
    v241: u16,
    #[od(index = 0x20F2, max = 243)]
    v242: u16,
    #[od(index = 0x20F3, max = 244)]
    v243: u16,
    #[od(index = 0x20F4, max = 245)]
    v244: u16,
    #[od(index = 0x20F5, max = 246)]
    v245: u16,
    #[od(index = 0x20F6, max = 247)]
    v246: u16,
    #[od(index = 0x20F7, max = 248)]
    v247: u16,
    #[od(index = 0x20F8, max = 249)]
    v248: u16,
    #[od(index = 0x20F9, max = 250)]
    v249: u16,
    #[od(index = 0x20FA, max = 251)]
    v250: u16,
    #[od(index = 0x20FB, max = 252)]
    v251: u16,
    #[od(index = 0x20FC, max = 253)]
    v252: u16,
    #[od(index = 0x20FD, max = 254)]
    v253: u16,
    #[od(index = 0x20FE, max = 255)]
    v254: u16,
    #[od(index = 0x20FF, max = 256)]
    v255: u16,
    #[od(index = 0x2100, max = 257)]
    v256: u16,
}

fn main() {}
